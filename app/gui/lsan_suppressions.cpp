// LeakSanitizer suppressions for leaks inside system libraries Qt loads (fontconfig caches,
// the D-Bus connection of the platform theme): they are not ours and would fail every ASan run
// of a Qt program. LSan calls this hook when it starts; without sanitizers it is never used.

extern "C" const char* __lsan_default_suppressions();  // NOLINT(bugprone-reserved-identifier)

extern "C" const char* __lsan_default_suppressions() {
  return "leak:libfontconfig.so\n"
         "leak:libdbus-1.so\n";
}
