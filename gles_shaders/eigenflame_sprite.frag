#version 300 es
// The flame's finished sprite at the model's resolution (plus the glow's
// margin): the gray image coloured through the ramp (HLS or a transfer
// function) and scaled by brightness, plus the blurred gray tinted with the
// ramp's mid colour. (HLS is linear in lightness up to L = 0.5, so for a glow
// that dim, tinting the blurred gray equals blurring the coloured image.) The billboard
// then only has to add one bilinear fetch of this per screen pixel.
precision highp float;

uniform sampler2D u_gray;  // reconstruction atlas
uniform sampler2D u_glow;  // glow atlas (half size)
uniform sampler2D u_ramp;
uniform vec4 u_gray_rect;  // texels (x, y, w, h)
uniform vec4 u_glow_rect;
uniform vec2 u_margin;     // glow margin, flame uv
uniform float u_brightness;
uniform float u_glow_strength;
uniform vec3 u_glow_tint;
uniform float u_edge_fade;  // share of the image's width (sides) and height (top) faded out
uniform vec2 u_foot_fade;   // heights (0 bottom, 1 top) over which the foot fades in; (0, 0): none
in vec2 v_uv;  // over this flame's sprite region, top row first
out vec4 o_colour;

vec2 atlas_uv(vec2 size, vec4 rect, vec2 q) {
  return (rect.xy + clamp(q * rect.zw, vec2(0.5), rect.zw - 0.5)) / size;
}

void main() {
  vec2 q = v_uv * (1.0 + 2.0 * u_margin) - u_margin;  // flame uv, t = 0 at the top
  vec3 c = vec3(0.0);
  if (q.x >= 0.0 && q.x <= 1.0 && q.y >= 0.0 && q.y <= 1.0) {
    float g = clamp(texture(u_gray, atlas_uv(vec2(textureSize(u_gray, 0)), u_gray_rect, q)).r, 0.0, 1.0);
    // A flame that reaches the image's sides or top (a wide fire, footage that
    // clipped it) would end on a straight line: fade it out there instead.
    if (u_edge_fade > 0.0)
      g *= smoothstep(0.0, u_edge_fade, min(min(q.x, 1.0 - q.x), q.y));
    // A model's own bed and logs, where the scene draws its own (a hearth).
    if (u_foot_fade.y > 0.0) g *= smoothstep(u_foot_fade.x, u_foot_fade.y, 1.0 - q.y);
    c = texture(u_ramp, vec2(g * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb * u_brightness;
  }
  if (u_glow_strength > 0.0)
    c += u_glow_tint * (texture(u_glow, atlas_uv(vec2(textureSize(u_glow, 0)), u_glow_rect, v_uv)).r * u_glow_strength);
  o_colour = vec4(c, 1.0);
}
