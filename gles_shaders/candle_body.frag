#version 300 es
// Wax lit by its own flame: diffuse light falling off with distance, and
// light scattered inside the wax near the top, both following the flame's
// size (so the wax flickers with it). The scatter is dim beside the flame
// (a bright rim reads as a second light: real close-ups show the flame
// alone above 60% of its brightness).
precision highp float;

in vec3 v_world;
in vec3 v_normal;
in vec3 v_wax;
in vec3 v_light_pos;
in float v_intensity;
in float v_kind;
in float v_top;
in float v_wick_t;
uniform vec3 u_camera;
out vec4 o_color;

void main() {
  vec3 flame = vec3(1.0, 0.7, 0.38);
  if (v_kind > 1.5) {
    // The wick: charred, glowing at its tip while the flame burns.
    vec3 c = mix(vec3(0.05, 0.04, 0.035), vec3(0.9, 0.35, 0.08), smoothstep(0.6, 1.0, v_wick_t) * min(v_intensity, 1.0));
    o_color = vec4(c, 1.0);
    return;
  }
  vec3 n = normalize(v_normal);
  vec3 to_light = v_light_pos - v_world;
  float d = length(to_light);
  float diffuse = max(dot(n, to_light / max(d, 1e-5)), 0.0) / (1.0 + d * d * 300.0);
  float depth = max(v_top - v_world.y, 0.0);
  float scatter = exp(-depth / 0.03);
  // A little view-dependent sheen on the melted pool.
  float sheen = 0.0;
  if (v_kind > 0.5) {
    vec3 h = normalize(normalize(u_camera - v_world) + to_light / max(d, 1e-5));
    float k = max(dot(n, h), 0.0);
    k *= k;
    k *= k;
    sheen = k * k * 0.2;
  }
  vec3 c = v_wax * (0.07 + flame * v_intensity * (0.5 * diffuse + 0.22 * scatter)) + flame * sheen * v_intensity;
  o_color = vec4(min(c, vec3(1.0)), 1.0);
}
