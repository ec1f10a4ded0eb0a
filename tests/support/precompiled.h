// tests/support/precompiled.h — the headers every test file includes, precompiled once for all
// test executables (tests/CMakeLists.txt). GoogleTest's header alone costs ~3 s of CPU to parse
// per file, against ~0.5 s to load the precompiled form: over 85 test files in both CI builds
// that is about 7 minutes of the 2-core CI machine (docs/PERFORMANCE.md, "CI").
// Only headers that do not depend on softmol's own macros belong here.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
