#version 300 es
// The flame and its glow, added onto the scene: the gray image coloured
// through the ramp (HLS or a transfer function), plus the blurred glow.
precision highp float;

uniform sampler2D u_gray;   // rows top-down: t = 1 - v
uniform sampler2D u_glow;
uniform sampler2D u_ramp;
uniform float u_brightness;
uniform float u_glow_strength;
in vec2 v_flame_uv;
in vec2 v_glow_uv;
out vec4 o_colour;

void main() {
  vec2 uv = v_flame_uv;
  vec3 c = vec3(0.0);
  if (uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0) {
    float g = clamp(texture(u_gray, vec2(uv.x, 1.0 - uv.y)).r, 0.0, 1.0);
    c = texture(u_ramp, vec2(g * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb;
  }
  c = c * u_brightness + texture(u_glow, v_glow_uv).rgb * u_glow_strength;
  o_colour = vec4(c, 1.0);
}
