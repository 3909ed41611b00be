// build_stamp.hpp — the commit a program was built from (FRONTSTEAL_GIT_COMMIT, stamped into every results
// file) and the folder of the embedded scenes (FRONTSTEAL_DATA_DIR). CMake's frontsteal_stamp(target) passes
// both; the fallbacks live here, once, so that a file compiled outside that function still builds and says
// "unknown" rather than a wrong commit.
#pragma once

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif
#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif
