#version 300 es
// The installer's test pattern: colour bars (top two thirds), a frame counter
// band, and a marker that crosses the screen once every period.
precision highp float;
precision highp int;

uniform vec2 u_resolution;
uniform float u_phase;  // 0..1: marker position across the screen
uniform int u_segments[8];  // the frame counter's digits, left to right, as segment masks
out vec4 o_color;

const vec3 kBars[8] = vec3[8](vec3(1.0), vec3(1.0, 1.0, 0.0), vec3(0.0, 1.0, 1.0), vec3(0.0, 1.0, 0.0),
                              vec3(1.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0), vec3(0.0));

// A seven-segment digit (segments a..g as the bits of m) at cell-local p in
// [0,1]^2 (y down). The digits' masks come from the CPU: a software GPU runs
// every branch for every pixel, and dividing the counter down per pixel was
// most of the pattern's cost.
float segment_digit(int m, vec2 p) {
  float t = 0.14;
  float on = 0.0;
  bool hx = p.x > t && p.x < 1.0 - t;
  bool left = p.x <= t, right = p.x >= 1.0 - t;
  bool top = p.y < 0.5, bottom = p.y >= 0.5;
  if ((m & 0x01) != 0 && hx && p.y < t) on = 1.0;                              // a
  if ((m & 0x02) != 0 && right && top) on = 1.0;                               // b
  if ((m & 0x04) != 0 && right && bottom) on = 1.0;                            // c
  if ((m & 0x08) != 0 && hx && p.y > 1.0 - t) on = 1.0;                        // d
  if ((m & 0x10) != 0 && left && bottom) on = 1.0;                             // e
  if ((m & 0x20) != 0 && left && top) on = 1.0;                                // f
  if ((m & 0x40) != 0 && hx && abs(p.y - 0.5) < t * 0.5) on = 1.0;            // g
  return on;
}

void main() {
  // Pixel coordinates with y down, so "top" means the top of the screen.
  vec2 px = vec2(gl_FragCoord.x, u_resolution.y - gl_FragCoord.y);
  vec2 uv = px / u_resolution;
  vec3 c;
  if (uv.y < 2.0 / 3.0) {
    c = kBars[clamp(int(uv.x * 8.0), 0, 7)];
  } else if (uv.y < 5.0 / 6.0) {
    // Counter band: 8 digits, left-aligned, white on black.
    c = vec3(0.0);
    float band = u_resolution.y / 6.0;
    float h = band * 0.7;
    float w = h * 0.55;
    vec2 q = vec2(px.x - band * 0.15, px.y - u_resolution.y * 2.0 / 3.0 - band * 0.15);
    int cell = int(floor(q.x / (w * 1.3)));
    vec2 local = vec2(mod(q.x, w * 1.3) / w, q.y / h);
    if (cell >= 0 && cell < 8 && local.x <= 1.0 && local.y >= 0.0 && local.y <= 1.0) {
      c = vec3(segment_digit(u_segments[cell], local));
    }
  } else {
    // Marker band: a white square on grey, its left edge at u_phase.
    c = vec3(0.25);
    float band = u_resolution.y / 6.0;
    float side = band * 0.8;
    float x0 = u_phase * (u_resolution.x - side);
    float y0 = u_resolution.y * 5.0 / 6.0 + band * 0.1;
    if (px.x >= x0 && px.x < x0 + side && px.y >= y0 && px.y < y0 + side) c = vec3(1.0);
  }
  // A one-pixel white border shows the mode's true edges.
  if (px.x < 1.0 || px.y < 1.0 || px.x > u_resolution.x - 1.0 || px.y > u_resolution.y - 1.0) c = vec3(1.0);
  o_color = vec4(c, 1.0);
}
