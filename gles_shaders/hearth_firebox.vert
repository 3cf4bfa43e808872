#version 300 es
// The firebox around a hearth: its back wall, splayed sides and floor, each a
// flat quad placed by hearth.cpp (position, the wall's own coordinates in
// metres, its normal and which surface it is).
precision highp float;

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_wall;    // metres along the surface, metres up (floor: across, in)
layout(location = 2) in vec3 a_normal;
layout(location = 3) in float a_surface;  // 0 back wall, 1 a side, 2 the floor

uniform mat4 u_view_projection;

out vec3 v_world;
out vec2 v_wall;
out vec3 v_normal;
flat out int v_surface;

void main() {
  v_world = a_position;
  v_wall = a_wall;
  v_normal = a_normal;
  v_surface = int(a_surface + 0.5);
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
