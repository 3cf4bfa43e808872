#version 300 es
// A hearth's logs, all instanced in one draw: the mesh (along, around, cap)
// wrapped round the axis from a_from to a_to, a little irregular (logs are
// not lathe-turned), with the end discs closing it.
precision highp float;

layout(location = 0) in vec3 a_mesh;   // along 0..1, around 0..1, cap -2..2 (0: the side)
layout(location = 1) in vec4 a_from;   // xyz, radius
layout(location = 2) in vec4 a_to;     // xyz, seed

uniform mat4 u_view_projection;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_log;  // along (m), around (0..1), 1 on the end discs
out float v_seed;
out float v_radius;
out vec4 v_axis;  // the log's direction; w: its radius (m)

void main() {
  vec3 axis = a_to.xyz - a_from.xyz;
  float len = length(axis);
  vec3 w = axis / len;
  vec3 u = normalize(abs(w.y) < 0.9 ? cross(w, vec3(0.0, 1.0, 0.0)) : cross(w, vec3(1.0, 0.0, 0.0)));
  vec3 v = cross(u, w);  // points mostly up
  float ang = a_mesh.y * 6.2831853;
  bool cap = a_mesh.z != 0.0;
  bool centre = abs(a_mesh.z) > 1.5;
  // Knobbly: the radius varies slowly along and around the log, with a few
  // knots (bumps where a branch was) that a straight, even cylinder lacks.
  float x = a_mesh.x;
  float r = a_from.w * (1.0 + 0.07 * sin(x * 9.0 + a_to.w) + 0.05 * sin(ang * 3.0 + a_to.w * 2.0) +
                        0.05 * sin(x * 23.0 + a_to.w * 3.0) * sin(ang * 5.0 + a_to.w));
  r *= 1.0 - 0.12 * smoothstep(0.9, 1.0, abs(x * 2.0 - 1.0));  // rounded ends
  // Trunks are not straight: the log bows sideways and a little up or down
  // along its length, its ends on the line from a_from to a_to.
  float bow = sin(3.14159265 * x);
  vec3 bend = (u * (0.4 * sin(a_to.w * 1.7)) + v * (0.2 * cos(a_to.w * 2.3))) * a_from.w * bow;
  vec3 radial = u * cos(ang) + v * sin(ang);
  vec3 p = a_from.xyz + axis * x + bend + (centre ? vec3(0.0) : radial * r);
  v_world = p;
  v_normal = cap ? w * sign(a_mesh.z) : radial;
  v_log = vec3(a_mesh.x * len, a_mesh.y, cap ? 1.0 : 0.0);
  v_seed = a_to.w;
  v_radius = centre ? 0.0 : 1.0;  // 0 at an end disc's centre, 1 on every rim vertex
  v_axis = vec4(w, a_from.w);
  gl_Position = u_view_projection * vec4(p, 1.0);
}
