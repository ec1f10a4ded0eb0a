// gl/gl_api.h — the OpenGL 4.5 core API as plain prototypes (Khronos glcorearb.h), resolved
// at link time against libOpenGL (glvnd). Included only by gl/*.cpp (STYLE.md practice 12).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
