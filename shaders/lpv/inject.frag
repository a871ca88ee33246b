#version 450 core
// Writes one injected point; the framebuffer's blending sums (or maxes) it into the cell.
flat in vec4 fValue0;
flat in vec4 fValue1;
flat in vec4 fValue2;
layout(location = 0) out vec4 out0;
layout(location = 1) out vec4 out1;
layout(location = 2) out vec4 out2;
void main() {
    out0 = fValue0;
    out1 = fValue1;
    out2 = fValue2;
}
