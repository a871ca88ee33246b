#version 450 core
layout(location = 0) in vec3 inPosition;
uniform mat4 uViewProjection;
out vec3 vPosition;
void main() {
    vPosition = inPosition;
    gl_Position = uViewProjection * vec4(inPosition, 1.0);
}
