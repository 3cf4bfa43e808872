#version 300 es
// One direction of the glow's separable Gaussian blur, at reduced size.
// The first pass reads the reconstructed gray image (zero outside it) and
// colours it through the ramp; the second blurs the first's result.
precision highp float;

uniform sampler2D u_source;
uniform sampler2D u_ramp;
uniform int u_colourise;      // 1: source is gray, colour it
uniform vec4 u_map;           // source uv = v_uv * u_map.xy + u_map.zw
uniform vec2 u_step;          // one tap, in source uv
uniform int u_radius;         // taps each side
uniform float u_sigma;        // in taps
in vec2 v_uv;
out vec4 o_colour;

void main() {
  vec2 uv = v_uv * u_map.xy + u_map.zw;
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int i = -u_radius; i <= u_radius; ++i) {
    float fi = float(i);
    float w = exp(-0.5 * fi * fi / (u_sigma * u_sigma));
    vec2 q = uv + u_step * fi;
    vec3 c;
    if (u_colourise == 1) {
      bool inside = q.x >= 0.0 && q.x <= 1.0 && q.y >= 0.0 && q.y <= 1.0;
      float g = inside ? clamp(texture(u_source, q).r, 0.0, 1.0) : 0.0;
      c = texture(u_ramp, vec2(g * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb;
    } else {
      c = texture(u_source, q).rgb;
    }
    sum += w * c;
    wsum += w;
  }
  o_colour = vec4(sum / wsum, 1.0);
}
