#version 300 es
// Wax bodies (side, melted top with rim and pool) and wicks, instanced.
precision highp float;

layout(location = 0) in vec4 a_vert;    // unit-circle x, z; y parameter; kind (0 side, 1 top, 2 wick)
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_place;   // bottom centre xyz, radius
layout(location = 3) in vec4 a_wax;     // height, wax rgb
layout(location = 4) in vec4 a_light;   // flame light position xyz, intensity

uniform mat4 u_view_projection;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_wax;
out vec3 v_light_pos;
out float v_intensity;
out float v_kind;
out float v_top;
out float v_wick_t;

const float kWickRadius = 0.0012;
const float kWickLength = 0.011;
const float kPoolDepth = 0.15;

void main() {
  float r = a_place.w;
  float h = a_wax.x;
  vec3 local;
  if (a_vert.w < 0.5) {
    local = vec3(a_vert.x * r, a_vert.z * h, a_vert.y * r);
  } else if (a_vert.w < 1.5) {
    local = vec3(a_vert.x * r, h + a_vert.z * r, a_vert.y * r);
  } else {
    local = vec3(a_vert.x * kWickRadius, h - kPoolDepth * r + a_vert.z * kWickLength, a_vert.y * kWickRadius);
  }
  v_world = a_place.xyz + local;
  v_normal = a_normal;
  v_wax = a_wax.yzw;
  v_light_pos = a_light.xyz;
  v_intensity = a_light.w;
  v_kind = a_vert.w;
  v_top = a_place.y + h;
  v_wick_t = a_vert.z;
  gl_Position = u_view_projection * vec4(v_world, 1.0);
}
