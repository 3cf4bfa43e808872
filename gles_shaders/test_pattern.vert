#version 300 es
// The installer's test pattern as flat rectangles (test_pattern.cpp lays
// them out per pixel): a corner in normalised device coordinates and the
// rectangle's colour.
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec3 a_color;
flat out vec3 v_color;
void main() {
  v_color = a_color;
  gl_Position = vec4(a_position, 0.0, 1.0);
}
