// Must NOT compile: irgs_core does not provide Qt (see tests/layering/CMakeLists.txt).
#include <QString>

int main() {
  return QString("core must stay Qt-free").isEmpty() ? 1 : 0;
}
