// rad-man-options PAGE: rewrites the option entries of rad's man page (docs/rad.1, between its
// `.\" BEGIN OPTIONS` and `.\" END OPTIONS` lines) from rad's command line definitions, so that
// the page says what --help says. Run it after changing an option; the test
// ManPage.OptionsAreTheHelps fails until then.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "app/cli.h"
#include "core/error.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fputs("usage: rad-man-options PAGE (docs/rad.1): rewrites its option entries\n", stderr);
    return 2;
  }
  const std::string path = argv[1];
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "%s: cannot read it\n", path.c_str());
    return 1;
  }
  const std::string page{std::istreambuf_iterator<char>(in), {}};
  try {
    const std::string made = rad::man_page_with_options(page);
    if (made == page) {
      std::printf("%s: up to date\n", path.c_str());
      return 0;
    }
    std::ofstream(path, std::ios::binary) << made;
    std::printf("%s: option entries rewritten from rad's command line\n", path.c_str());
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), e.message().c_str());
    return 1;
  }
  return 0;
}
