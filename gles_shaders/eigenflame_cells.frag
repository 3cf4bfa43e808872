#version 300 es
// Which cells of a flame's billboard grid (eigenflame.vert) can add any light:
// 1 where a sprite texel that the cell's pixels may read (eigenflame.frag's
// bilinear fetch, one texel more on every side) is not black, 0 where all of
// them are. The billboard leaves the black cells out: the same picture, from
// fewer pixels (most of a screen-high billboard is black around its flame).
// One fragment per cell (x: column, y: row from the billboard's base).
precision highp float;
precision highp int;

uniform sampler2D u_sprite;  // the sprite atlas
uniform vec4 u_sprite_rect;  // this flame's sprite, texels (x, y, w, h)
uniform ivec2 u_origin;      // this flame's cells in the target
uniform vec2 u_cells;        // columns, rows
out vec4 o_live;

void main() {
  ivec2 cell = ivec2(gl_FragCoord.xy) - u_origin;
  // The cell's v_glow_uv (top row first): x over [c, c + 1] / columns, y
  // over 1 - [r + 1, r] / rows.
  vec2 lo = vec2(float(cell.x) / u_cells.x, 1.0 - float(cell.y + 1) / u_cells.y);
  vec2 hi = vec2(float(cell.x + 1) / u_cells.x, 1.0 - float(cell.y) / u_cells.y);
  vec2 size = u_sprite_rect.zw;
  ivec2 t0 = max(ivec2(floor(clamp(lo * size, vec2(0.5), size - 0.5) - 0.5)) - 1, ivec2(0));
  ivec2 t1 = min(ivec2(floor(clamp(hi * size, vec2(0.5), size - 0.5) - 0.5)) + 2,
                 ivec2(size) - 1);
  ivec2 at = ivec2(u_sprite_rect.xy);
  float m = 0.0;
  for (int y = t0.y; y <= t1.y; ++y)
    for (int x = t0.x; x <= t1.x; ++x)
      m = max(m, dot(texelFetch(u_sprite, at + ivec2(x, y), 0).rgb, vec3(1.0)));
  o_live = vec4(m > 0.0 ? 1.0 : 0.0, 0.0, 0.0, 1.0);
}
