#version 300 es
// The test pattern's rectangles (test_pattern.vert): one flat colour each.
precision mediump float;
flat in vec3 v_color;
out vec4 o_color;
void main() { o_color = vec4(v_color, 1.0); }
