#version 300 es
// Candle flames, all instanced in one draw: each vertex of the mesh over the
// still is moved by the Beier-Neely warp from the still's control lines
// (u_src) to this candle's morphed lines (forward mapping, as in the candle
// paper), then placed on a camera-facing billboard that rotates about the
// flame's base for front-back sway. Mirrors beier_neely() in
// firmware/elements/candle/flame_warp.cpp.
precision highp float;

layout(location = 0) in vec2 a_src;  // mesh vertex on the still, billboard units
layout(location = 1) in vec4 a_l0;   // destination lines: (P.xy, Q.xy)
layout(location = 2) in vec4 a_l1;
layout(location = 3) in vec4 a_l2;
layout(location = 4) in vec4 a_l3;
layout(location = 5) in vec4 a_l4;
layout(location = 6) in vec4 a_l5;
layout(location = 7) in vec4 a_l6;
layout(location = 8) in vec4 a_l7;
layout(location = 9) in vec4 a_l8;
layout(location = 10) in vec4 a_l9;
layout(location = 11) in vec4 a_anchor;  // flame base in the world (xyz), metres per unit
layout(location = 12) in vec4 a_pose;    // front-back tilt (rad), line count, brightness, -

uniform mat4 u_view_projection;
uniform vec3 u_camera;
uniform vec4 u_src[10];  // the still's own lines
uniform vec3 u_weights;  // Beier-Neely a, b, p
uniform float u_aspect;  // still width / height
uniform float u_base;    // rotation centre height on the still

out vec2 v_uv;
out float v_bright;

void main() {
  vec4 dst[10];
  dst[0] = a_l0; dst[1] = a_l1; dst[2] = a_l2; dst[3] = a_l3; dst[4] = a_l4;
  dst[5] = a_l5; dst[6] = a_l6; dst[7] = a_l7; dst[8] = a_l8; dst[9] = a_l9;
  int n = int(a_pose.y + 0.5);
  vec2 x = a_src;
  vec2 sum = vec2(0.0);
  float wsum = 0.0;
  for (int i = 0; i < 10; ++i) {
    if (i >= n) break;
    vec2 p = u_src[i].xy, q = u_src[i].zw;
    vec2 d = q - p;
    float len2 = dot(d, d);
    if (len2 <= 1e-12) continue;
    float len = sqrt(len2);
    vec2 e = x - p;
    float u = dot(e, d) / len2;
    float v = dot(e, vec2(-d.y, d.x)) / len;
    vec2 p2 = dst[i].xy, q2 = dst[i].zw;
    vec2 d2 = q2 - p2;
    float len_b = length(d2);
    vec2 m = p2 + u * d2;
    if (len_b > 1e-9) m += v * vec2(-d2.y, d2.x) / len_b;
    float dist = u < 0.0 ? length(e) : (u > 1.0 ? length(x - q) : abs(v));
    float w;
    if (u_weights.y == 2.0 && u_weights.z == 0.5) {
      w = len / ((u_weights.x + dist) * (u_weights.x + dist));  // the default a, b = 2, p = 1/2
    } else {
      w = pow(pow(len, u_weights.z) / (u_weights.x + dist), u_weights.y);
    }
    sum += m * w;
    wsum += w;
  }
  vec2 moved = wsum > 0.0 ? sum / wsum : x;

  vec3 base = a_anchor.xyz;
  float s = a_anchor.w;
  vec3 f = u_camera - base;
  f.y = 0.0;
  f = length(f) > 1e-5 ? normalize(f) : vec3(0.0, 0.0, 1.0);
  vec3 right = vec3(f.z, 0.0, -f.x);
  vec3 up = vec3(0.0, cos(a_pose.x), 0.0) + f * sin(a_pose.x);
  vec3 world = base + right * (moved.x * s) + up * ((moved.y - u_base) * s);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_uv = vec2(a_src.x / u_aspect + 0.5, 1.0 - a_src.y);
  v_bright = a_pose.z;
}
