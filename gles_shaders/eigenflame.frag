#version 300 es
// The flame with its glow, added onto the scene: one bilinear fetch of the
// flame's finished sprite (eigenflame_sprite.frag) from the shared atlas.
precision highp float;

uniform sampler2D u_sprite;
uniform vec4 u_sprite_rect;  // texels (x, y, w, h)
in vec2 v_glow_uv;           // over the sprite, top row first
out vec4 o_colour;

void main() {
  vec2 size = vec2(textureSize(u_sprite, 0));
  vec2 a = (u_sprite_rect.xy + clamp(v_glow_uv * u_sprite_rect.zw, vec2(0.5), u_sprite_rect.zw - 0.5)) / size;
  o_colour = vec4(texture(u_sprite, a).rgb, 1.0);
}
