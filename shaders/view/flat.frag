#version 450 core
// Debug geometry colours are display values already (no tone mapping).
in vec3 vColor;
out vec4 outColor;
void main() { outColor = vec4(vColor, 1.0); }
