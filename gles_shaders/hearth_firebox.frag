#version 300 es
// The firebox's static look, rendered once into the hearth's cache (see
// hearth.cpp) with the logs: old firebrick in running bond, each brick its own
// tone, pitted, with recessed grey mortar; soot blackening the back wall above
// the fire in streaks and fading out to the sides; the floor a bed of pale ash
// over larger bricks. Lit by the fire as three lights spread along its width.
// Out, in the second target (the logs' crack texture, RGBA8, so the
// per-frame pass reads one texel): the lit colour at half scale as its square
// root (8 bits then band less in the dark bricks) and how much of the light
// comes from the fire's left half, so hearth_firebox_shade.frag can flicker
// each half on its own. The first target (the logs' colour) is not used.
precision highp float;

in vec3 v_world;
in vec2 v_wall;
in vec3 v_normal;
flat in int v_surface;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_side;

uniform vec3 u_light_pos;   // the middle of the fire
uniform float u_spread;     // half the distance between the outer lights (m, along x)
uniform vec3 u_light;       // the light's colour times its strength
uniform vec3 u_brick;
uniform float u_soot;

// Running bond: x the distance to the nearest mortar line (m), y the brick's hash.
vec2 bricks(vec2 p, vec2 size) {
  float row = floor(p.y / size.y);
  float u = p.x + (mod(row, 2.0) > 0.5 ? 0.5 * size.x : 0.0);
  vec2 cell = vec2(floor(u / size.x), row);
  vec2 f = vec2(u, p.y) - cell * size;
  float d = min(min(f.x, size.x - f.x), min(f.y, size.y - f.y));
  return vec2(d, hash(cell + 3.7));
}

void main() {
  vec3 n = normalize(v_normal);
  bool floor_surface = v_surface == 2;
  vec2 size = floor_surface ? vec2(0.23, 0.115) : vec2(0.225, 0.075);
  // The mortar lines wander a little: hand-laid, not ruled.
  vec2 p = v_wall + 0.004 * (vec2(noise(v_wall * 9.0), noise(v_wall * 9.0 + 5.0)) - 0.5);
  vec2 b = bricks(p, size);
  float mortar = 1.0 - smoothstep(0.003, 0.008, b.x);
  // Fired clay: a faint mottle and a few pits, soft (from across a room a
  // brick's face is nearly even; its tone differs from its neighbours').
  float pits = smoothstep(0.62, 0.85, noise(v_wall * 90.0));
  float grain = fbm(v_wall * vec2(18.0, 26.0));
  vec3 brick = u_brick * (0.8 + 0.3 * b.y) * (0.85 + 0.25 * grain) * (1.0 - 0.15 * pits);
  brick = mix(brick, vec3(dot(brick, vec3(0.3, 0.5, 0.2))), 0.25 * hash(vec2(b.y * 17.0, 1.0)));
  vec3 colour = mix(brick, brick * 0.55 + vec3(0.03) * grain, mortar);
  float soot = 0.0;
  if (floor_surface) {
    // Ash lies thick near the fire and thins out towards the walls.
    float ash = smoothstep(0.35, 0.75, fbm(v_wall * 6.0) + 0.5 - 0.6 * length(v_world.xz - u_light_pos.xz));
    colour = mix(colour * 0.6, vec3(0.3, 0.29, 0.27) * (0.7 + 0.5 * grain), ash);
  } else {
    // Soot: heaviest above the fire, rising in streaks, fading to the sides
    // and near the floor (where ash and heat keep the brick pale).
    // The plume widens as it rises; soot is a dull grey-black film, not a hole.
    float across = abs(v_world.x - u_light_pos.x) / max(u_spread * (1.2 + 2.0 * v_wall.y), 0.05);
    float streaks = fbm(vec2(v_wall.x * 6.0, v_wall.y * 1.5));
    soot = smoothstep(0.05, 0.5, v_wall.y) * (1.0 - smoothstep(0.4, 1.2, across + 0.5 * streaks)) +
           0.3 * smoothstep(0.3, 1.0, v_wall.y) * streaks;
    // Years of fires film the whole box, unevenly: the courses show through
    // it only where the fire lights them (bricks drawn crisp everywhere read
    // as a wallpaper).
    soot = max(soot, 0.5 * smoothstep(0.3, 0.75, fbm(v_wall * vec2(3.0, 2.0) + 9.0) + 0.2 * streaks));
    soot = clamp(soot * u_soot * (0.7 + 0.5 * streaks), 0.0, 0.85);
    colour = mix(colour, vec3(0.035, 0.03, 0.028) * (0.7 + 0.6 * grain), soot);
  }
  // The fire's light: three points along its width, each falling off with distance.
  vec3 light = vec3(0.0);
  float left = 0.0, total = 0.0;
  for (int i = -1; i <= 1; ++i) {
    vec3 to = u_light_pos + vec3(float(i) * u_spread, 0.0, 0.0) - v_world;
    float d2 = dot(to, to);
    // A flame is near: the light falls off fast (inverse square, softened
    // within a flame's size), and faster still beyond about half a metre (the
    // logs and the flames' own smoke shade it), so the box is lit around the
    // fire and dark at its far corners, as in real footage, not evenly.
    float l = max(dot(n, to * inversesqrt(max(d2, 1e-6))), 0.0) * 0.06 / (0.03 + d2) *
              exp(-2.5 * max(d2 - 0.2, 0.0));
    total += l;
    left += i < 0 ? l : (i == 0 ? 0.5 * l : 0.0);
  }
  light = u_light * total / 3.0 * 2.2 + vec3(0.01, 0.008, 0.006);
  o_colour = vec4(0.0);
  o_side = vec4(sqrt(min(colour * light * 0.5, vec3(1.0))), total > 0.0 ? left / total : 0.5);
}
