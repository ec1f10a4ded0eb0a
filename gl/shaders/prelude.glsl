#version 450 core
// gl/shaders/prelude.glsl — GLSL side of the shared-formula subset (C++ side:
// raster/shared/prelude.h). gl/program.cpp prepends it to every pass, then the generated
// layout #defines (gl/prim_layout.cpp), then the shared .inc files, then the pass itself.
#define SM_FN
#define SM_PRECISE precise
#define SM_INOUT(T) inout T
