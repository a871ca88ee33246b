// Per-pixel passes as compute dispatches (shaders/common/screen_pass.glsl): one invocation per
// pixel of a rectangle, in square groups (shaders/shared/screen_pass.h).
//
// Why compute and not a full-screen triangle: on NVIDIA's data-centre GPUs (H100, H200) only a
// few of the SMs can run vertex and fragment shaders, so a per-pixel pass drawn as a triangle
// ran there on a small part of the chip (docs/gpu.md measures it), while a compute dispatch
// runs on all of it; on other GPUs and on llvmpipe the two cost about the same.
#pragma once

#include "gl/program.h"

namespace voxgi::gl {

struct ScreenRect {
    int x = 0, y = 0, width = 0, height = 0;
};

// Runs `program` (made current here) over `rect`: sets its uScreenRect and dispatches enough
// groups. The caller binds the program's textures and images first and issues the barrier
// that its readers need (screenPassBarrier()).
void dispatchScreen(const Program& program, ScreenRect rect);

// The barrier after a pass that wrote images: its writes are seen by later draws and blending,
// texture fetches, image loads and read-backs.
void screenPassBarrier();

// Adds `program`'s values into the framebuffer bound for drawing now, as a full-screen draw with
// additive blending (GL_ONE, GL_ONE) would: its first colour attachment (an RGBA32F texture) is
// bound as image `uAdditiveTarget` on `imageUnit`, and the pass covers the viewport, clipped to
// the scissor box when the scissor test is on. Throws GlError when the bound target is the
// default framebuffer or not RGBA32F.
void addToBoundTarget(const Program& program, GLuint imageUnit = 7);

}  // namespace voxgi::gl
