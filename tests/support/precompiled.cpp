// tests/support/precompiled.cpp — the translation unit that builds tests/support/precompiled.h's
// precompiled header; every test executable reuses it (tests/CMakeLists.txt).
#include "tests/support/precompiled.h"
