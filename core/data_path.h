// Where RTDR's data files are found: the shipped scenes, the SPIR-V shaders and the chart scripts. In a build
// tree they live where the build left them (scenes/ and eval/ of the source tree, shaders/ of the build folder);
// `cmake --install` copies them to <prefix>/share/rtdr/ (cmake/install.cmake), and an installed program finds
// them there, whatever happens to the source tree and the build folder afterwards.
#pragma once

#include <string>

namespace rtdr {

// The path of `relative` (e.g. "scenes", "eval/charts.py"), the first that exists of:
//   1. $RTDR_DATA_DIR/<relative>, when the variable is set (a program linking the installed libraries, installed
//      elsewhere than its configured prefix: the package's rtdr_DATA_DIR);
//   2. <the running program's folder>/../share/rtdr/<relative> (an installed rtdr: <prefix>/bin/rtdr);
//   3. `build_tree` (the source or build folder this binary was built from, compiled in);
//   4. <the configured install prefix>/share/rtdr/<relative> (a program linking the installed libraries).
// When none exists, `build_tree`, so that an error message names where it was looked for first in a build.
std::string data_path(const std::string& relative, const std::string& build_tree);

// The installed data folder of the configured prefix, <prefix>/share/rtdr (for messages).
std::string installed_data_dir();

}  // namespace rtdr
