// irgs-summary: the session summary of a recording (issue 6, item 8) from the command line.
//   irgs-summary RECORDING.irgsrec OUT.md|OUT.html
// Prints nothing on success; exit status 1 with the reason on stderr when the recording cannot
// be read or the output not written, 2 for bad arguments.

#include <QCoreApplication>
#include <cstdio>
#include <string>

#include "app/recording/recording_reader.hpp"
#include "app/recording/session_summary.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: irgs-summary RECORDING.irgsrec OUT.md|OUT.html\n"
                 "  Writes the session summary (duration, distance, link quality, events) of a\n"
                 "  session recording as Markdown or HTML (by the output's extension).\n");
    return 2;
  }
  QCoreApplication app(argc, argv);  // Qt Sql loads its driver through the application
  const std::string input = argv[1];
  const std::string output = argv[2];
  irgs::recording::LoadResult loaded = irgs::recording::loadRecording(input);
  if (!loaded.recording) {
    std::fprintf(stderr, "irgs-summary: %s\n", loaded.error.c_str());
    return 1;
  }
  for (const std::string& warning : loaded.warnings)
    std::fprintf(stderr, "irgs-summary: warning: %s\n", warning.c_str());
  const irgs::recording::SessionSummary summary =
      irgs::recording::summarizeRecording(*loaded.recording, input);
  if (const std::string error = irgs::recording::writeSummary(summary, output); !error.empty()) {
    std::fprintf(stderr, "irgs-summary: %s\n", error.c_str());
    return 1;
  }
  return 0;
}
