#version 300 es
// The shutter's trail (perlinfire.cpp): drawn over the Perlin fire's
// offscreen target with a reverse-subtract blend, it keeps the shutter's
// share of what earlier frames left (the blend colour's alpha) less one step
// of 8 bits, so a fading trail ends at zero instead of sticking at its last
// level. Drawn with fullscreen.vert.
precision mediump float;
out vec4 o_color;
void main() { o_color = vec4(1.0 / 255.0); }
