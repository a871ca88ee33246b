// The frame's G-buffer as the deferred passes read it: its four textures (bound by the frame
// renderer and the techniques under these names) and one pixel's texels, for decodeGBuffer
// (shaders/shared/gbuffer.h).
#ifndef VOXGI_GBUFFER_TEXTURES_GLSL
#define VOXGI_GBUFFER_TEXTURES_GLSL
#include "shared/gbuffer.h"

uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;

GBufferTexels fetchGBuffer(ivec2 pixel) {
    GBufferTexels t;
    t.position = texelFetch(uPosition, pixel, 0);
    t.normal = texelFetch(uNormal, pixel, 0);
    t.albedo = texelFetch(uAlbedo, pixel, 0);
    t.emission = texelFetch(uEmission, pixel, 0);
    return t;
}
#endif
