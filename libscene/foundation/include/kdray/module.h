// kdray's run-time modules: shared libraries loaded with dlopen on first use, so that tools which
// never decode or write an image do not load OpenImageIO (some 250 shared libraries, about 0.2 s
// at every start). They live in lib/kdray/ beside the folder of the executables: one level up
// when installed (PREFIX/bin/kdrender, PREFIX/lib/kdray/), two in the build tree
// (build/tools/kdrender/kdrender, build/lib/kdray/), so a relocated or installed copy works.
#pragma once

#include <string>

namespace kdray {

// Loads module `file_name` (or the file the environment variable `override_variable` names) and
// returns the address of its symbol `symbol`; nullptr, with `problem` saying why, when either is
// missing. A module stays loaded for the life of the process.
void* load_module_symbol(const char* file_name, const char* override_variable, const char* symbol,
                         std::string& problem);

}  // namespace kdray
