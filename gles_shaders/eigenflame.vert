#version 300 es
// The flame's billboard: a grid over the flame image (u across, v up from
// the base) plus the glow's margin, facing the camera around the vertical.
// Rigid: the image keeps its aspect. Deformed (Learning Flames' inverse
// normalisation, spline-interpolated on the CPU per grid row): row v of the
// normalised image is centred at u_shape[row].x and u_shape[row].y wide, at
// height u_base + v * u_height (all in flame-image heights).
precision highp float;

#ifndef SHAPE_ROWS
#define SHAPE_ROWS 24
#endif

uniform mat4 u_view_projection;
uniform vec3 u_origin;        // bottom centre of the flame image, world
uniform vec3 u_right;         // world direction of +u (unit)
uniform vec2 u_size;          // flame image width and height, world
uniform vec4 u_margin;        // glow margin in flame uv: left, right, bottom, top
uniform vec2 u_shape[SHAPE_ROWS + 1];  // per row: centre offset, width factor
uniform float u_base;         // deformed: base height
uniform float u_height;       // deformed: base-to-tip length
uniform int u_deform;         // 0: rigid

#ifndef GRID_COLUMNS
#define GRID_COLUMNS 8
#endif
uniform highp sampler2D u_cells;  // eigenflame_cells.frag: 0 where the cell is black
uniform int u_cells_row;          // this flame's first row there

in vec2 a_grid;   // 0..1 over the whole billboard
in float a_cell;  // the grid cell this vertex's triangle lies in: row * GRID_COLUMNS + column
out vec2 v_glow_uv;   // over the sprite (flame + glow margin), top row first

void main() {
  // A cell that adds no light (black sprite texels all over it): its
  // triangles put outside the view, where they cost nothing.
  int cell = int(a_cell);
  if (texelFetch(u_cells, ivec2(cell % GRID_COLUMNS, u_cells_row + cell / GRID_COLUMNS), 0).r == 0.0) {
    v_glow_uv = vec2(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec2 uv = vec2(mix(-u_margin.x, 1.0 + u_margin.y, a_grid.x),
                 mix(-u_margin.z, 1.0 + u_margin.w, a_grid.y));
  v_glow_uv = vec2(a_grid.x, 1.0 - a_grid.y);  // the glow texture is stored top row first
  float x = (uv.x - 0.5) * u_size.x / u_size.y;
  float y = uv.y;
  if (u_deform == 1) {
    float r = clamp(uv.y, 0.0, 1.0) * float(SHAPE_ROWS);
    int i = int(min(floor(r), float(SHAPE_ROWS - 1)));
    vec2 s = mix(u_shape[i], u_shape[i + 1], r - float(i));
    x = s.x + (uv.x - 0.5) * s.y;
    y = u_base + uv.y * u_height;
  }
  vec3 p = u_origin + (u_right * x + vec3(0.0, y, 0.0)) * u_size.y;
  gl_Position = u_view_projection * vec4(p, 1.0);
}
