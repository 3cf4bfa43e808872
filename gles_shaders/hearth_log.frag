#version 300 es
// A burning log's static look, rendered once into the hearth's cache (see
// hearth.cpp): rough bark in deep, ragged furrows along the log; charred
// black where the fire licks it (the top and the side facing the fire) and
// along its underside over the coals, the char broken into blocks whose
// cracks glow; pale end grain with rings and a burnt rim. Out: the unlit
// colour (RGB10_A2), the cracks' glow (two 8-bit halves) with their
// pulse's two hashes, and the surface's normal with the relief of the bark's
// plates and fissures and of the char's blocks (RGBA8, 0.5 + 0.5 n), so the
// firelight picks out the relief: lit from one side, a fissure's far wall
// catches the light and its near wall falls dark, where a colour alone reads
// as paint on a smooth tube. hearth_log_shade.frag lights it and pulses the cracks
// every frame, so the noise here (value_noise.frag) runs only when the view
// changes.
precision highp float;

in vec3 v_world;
in vec3 v_normal;
in vec3 v_log;
in float v_seed;
in float v_radius;
in vec4 v_axis;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_crack;
layout(location = 2) out vec4 o_normal;

uniform vec3 u_light_pos;
uniform vec3 u_bark;

// Char blocks: distance to the nearest cell border of a jittered grid (the
// cracks) and the cell's own hash (each block burns and pulses on its own).
vec2 char_cells(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  float d1 = 8.0, d2 = 8.0, id = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec2 g = vec2(float(x), float(y));
      vec2 o = g + 0.15 + 0.7 * vec2(hash(i + g), hash(i + g + 17.0)) - f;
      float d = dot(o, o);
      if (d < d1) {
        d2 = d1;
        d1 = d;
        id = hash(i + g + 5.0);
      } else if (d < d2) {
        d2 = d;
      }
    }
  return vec2(sqrt(d2) - sqrt(d1), id);
}

// The bark's plates: 1 on a plate, 0 in the fissures between them, which
// wander along the log (q.y) and break across it, so the surface reads as
// rough relief at every scale, not as smooth stripes.
float bark_plate(vec2 q) {
  vec2 b = vec2(q.x * 2.6, q.y * 0.9);
  b.x += 0.8 * fbm(q * vec2(0.9, 0.45) + 11.0);  // fissures wander
  float fissure = 1.0 - abs(2.0 * fbm(b) - 1.0);  // 1 on the plate, 0 in a fissure
  float across = fbm(vec2(q.x * 1.2 + 5.0, q.y * 3.5));  // plates break along the log
  return smoothstep(0.35, 0.75, fissure) * smoothstep(0.2, 0.45, across);
}
float bark_rough(vec2 q) { return fbm(q * vec2(11.0, 4.0) + 3.0); }  // the plates' own texture
// Alligator char: blocks about as long as they are wide (2-3 cm: larger
// ones read as a tortoise shell), not long strips along the log.
vec2 char_blocks(vec2 q) { return char_cells(vec2(q.x * 2.0, q.y * 8.0)); }
// The blocks' low dome: each rounded, lighter and higher in its middle.
float char_dome(vec2 cell) { return smoothstep(0.0, 0.15, cell.x); }

// The relief (m) at q: the bark's plates stand about 4 mm proud of its
// fissures, rough on top; the char's blocks are rough, between cracks up to
// 2 mm deep, only some of them that deep (every crack as deep drew a net
// of even grooves: snakeskin, cobbles).
float relief(vec2 q, float char_amount) {
  float rough = bark_rough(q);
  float bark = 0.004 * bark_plate(q) + 0.001 * rough;
  float deep = 0.2 + 0.8 * smoothstep(0.4, 0.8, noise(q * vec2(1.7, 5.0) + 53.0));
  float char_height = 0.002 * deep * char_dome(char_blocks(q)) + 0.0008 * rough;
  return mix(bark, char_height, char_amount);
}

// The side's normal with the relief: its slope along the log and around it,
// taken over about a pixel's footprint (so detail finer than a pixel evens
// out instead of sparkling). q: the bark's coordinates (around * 14, along (m)
// * 5).
vec3 relief_normal(vec3 n, vec2 q, float char_amount) {
  vec2 eps = max(fwidth(q), vec2(0.004));
  float h = relief(q, char_amount);
  float dx = (relief(q + vec2(eps.x, 0.0), char_amount) - h) / eps.x;  // per unit of q.x
  float dy = (relief(q + vec2(0.0, eps.y), char_amount) - h) / eps.y;
  vec3 along = normalize(v_axis.xyz - n * dot(v_axis.xyz, n));
  vec3 around = cross(n, along);  // the way q.x grows (hearth_log.vert's angle)
  // q.x runs 14 units round the log, q.y 5 units a metre along it.
  float per_m_around = 14.0 / (6.2831853 * v_axis.w);
  return normalize(n - around * (dx * per_m_around) - along * (dy * 5.0));
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 shaded = n;  // with the relief
  float facing = max(dot(n, normalize(u_light_pos - v_world)), 0.0);
  vec3 colour;
  o_crack = vec4(0.0);
  if (v_log.z > 0.5) {
    // End grain: faint rings in wood darkened by the heat, burnt black
    // towards the rim. Pale sawn wood reads as a lit disc at the end of every
    // log (real fireplace logs' ends are sooted or charred).
    float r = v_radius;
    float rings = 0.5 + 0.5 * sin(r * 40.0 + noise(vec2(r * 9.0, v_seed)) * 3.0);
    colour = mix(vec3(0.15, 0.1, 0.065), vec3(0.1, 0.068, 0.045), rings) * (1.0 - 0.85 * smoothstep(0.5, 0.9, r));
  } else {
    vec2 q = vec2(v_log.y * 14.0 + v_seed, v_log.x * 5.0);
    // Bark: thick plates split by deep fissures.
    float plate = bark_plate(q);
    float rough = bark_rough(q);
    // Weathered bark is grayer than the wood beneath it. The plates stand
    // out little: in a fireplace's light bark reads as dark and rough; plates
    // twice as bright as their fissures read as painted planks.
    vec3 bark = mix(u_bark, vec3(dot(u_bark, vec3(0.3, 0.5, 0.2))), 0.35);
    // From across a room the fissures are a shade darker than the plates, not
    // black grooves: dense dark grooves read as the grain of sawn planks.
    // Patches a hand long, lighter and darker, break the log's length.
    float blotch = 0.75 + 0.5 * fbm(q * vec2(0.35, 0.25) + 29.0);
    colour = bark * blotch * (0.42 + 0.42 * plate * (0.7 + 0.6 * rough));
    colour += vec3(0.05, 0.047, 0.04) * smoothstep(0.72, 0.95, noise(q * vec2(3.0, 0.8) + 41.0)) * plate;
    // Char: where the fire reaches (up, and towards the light) and along the
    // underside that lies on the coals, with a ragged edge.
    float edge = 0.4 * (fbm(q * 1.1 + vec2(0.0, v_seed)) - 0.5);
    float above = clamp(facing * 0.7 + n.y * 0.5, 0.0, 1.0);
    float below = smoothstep(-0.05, -0.55, n.y);
    float char_amount = max(smoothstep(0.3, 0.65, above + edge), smoothstep(0.3, 0.8, below + edge));
    vec2 cell = char_blocks(q);
    // The blocks: dull black with a faint sheen, darker toward their cracks,
    // each rounded (lighter in the middle) so the char has relief.
    // Under firelight a strong dome made the blocks read as cobbles: the
    // relief is kept faint, the seams narrow.
    float dome = char_dome(cell);
    vec3 char_colour = vec3(0.045, 0.038, 0.033) * (0.9 + 0.2 * cell.y) * (0.8 + 0.2 * dome);
    // Grey ash on some blocks' crowns, most where the fire is hottest; dull,
    // as pale crowns on every block read as cobblestones.
    // Grey ash lies in soft patches a hand across, most where the fire is
    // hottest, a film over several blocks (ash on each block's crown, or
    // any lighter crown, reads as gravel or cobbles from across a room).
    float ash = smoothstep(0.55, 0.85, fbm(q * vec2(1.3, 3.0) + 7.0) + 0.25 * above - 0.15) *
                smoothstep(0.02, 0.12, cell.x);
    char_colour = mix(char_colour, vec3(0.16, 0.15, 0.14) * (0.75 + 0.25 * rough), 0.45 * ash);
    colour = mix(colour, char_colour, char_amount);
    shaded = relief_normal(n, q, char_amount);
    // Cracks between the blocks glow where the fire licks (the underside's
    // glow is hearth_log_shade.frag's); not every crack at once.
    // Only a few blocks' borders glow, and those in broken runs, so the glow
    // reads as embers in the deepest fissures, not as a drawn network or as
    // sparkles scattered over the log; a crack is a soft, hot seam wider than
    // the char's dark gap.
    // A seam under about two pixels wide (far or edge-on logs) breaks into a
    // dotted line of bright pixels: it widens to two pixels and dims to keep
    // its glow.
    float seam = max(0.2, 2.0 * fwidth(cell.x));
    float crack = smoothstep(seam, 0.0, cell.x) * (0.2 / seam) * char_amount;
    crack *= smoothstep(0.7, 0.9, cell.y);
    crack *= smoothstep(0.5, 0.7, fbm(q * vec2(2.0, 6.0) + 23.0)) * smoothstep(0.35, 0.8, above);
    // A block's whole border aglow reads as a drawn ring: noise finer than a
    // block breaks each border into one or two glowing runs.
    crack *= smoothstep(0.45, 0.65, noise(q * vec2(6.0, 24.0) + 61.0));
    // 16 bits over two channels: the glow is bright, 8 would band it.
    float hi = floor(crack * 255.0) / 255.0;
    o_crack = vec4(hi, (crack - hi) * 255.0, cell.y, hash(vec2(cell.y * 91.0, 3.0)));
  }
  o_colour = vec4(colour, 1.0);
  o_normal = vec4(0.5 + 0.5 * shaded, 1.0);
}
