#version 300 es
// The flame with its glow, added onto the scene: one bilinear fetch of the
// flame's finished sprite (eigenflame_sprite.frag) from the shared atlas.
precision highp float;

uniform sampler2D u_sprite;
uniform vec4 u_sprite_rect;  // texels (x, y, w, h)
uniform float u_light;       // the flame's flicker this frame (1: as drawn)
in vec2 v_glow_uv;           // over the sprite, top row first
out vec4 o_colour;

void main() {
  vec2 size = vec2(textureSize(u_sprite, 0));
  vec2 a = (u_sprite_rect.xy + clamp(v_glow_uv * u_sprite_rect.zw, vec2(0.5), u_sprite_rect.zw - 0.5)) / size;
  vec3 c = texture(u_sprite, a).rgb;
  // The flicker is the burning body's: the bright flame flickers, its dim
  // edge and the glow around it hardly do (the outline keeps its breathing).
  float body = smoothstep(0.35, 0.9, dot(c, vec3(0.299, 0.587, 0.114)));
  o_colour = vec4(c * (1.0 + (u_light - 1.0) * body), 1.0);
}
