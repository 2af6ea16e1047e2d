#version 330 core
// Display of the progressive accumulation: the CPU uploads radiance sums, the
// mapping to the screen happens only here, so exposure and gamma never touch
// the samples.
in vec2 uv;
out vec4 colour;

uniform sampler2D sums;      // RGB radiance sums
uniform sampler2D sums_sq;   // per-pixel sum of squared luminance
uniform float spp;           // samples per pixel in `sums`
uniform float exposure;      // linear scale; 1/255^2.2 is the report's mapping
uniform float gamma;         // 2.2 in the report
uniform int mode;            // 0 image, 1 relative standard error per pixel
uniform vec3 lum_weights;    // as used for sums_sq
uniform int tonemap;         // 0 the report's (clip at white), 1 ACES filmic

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a rational fit of the
// ACES reference rendering transform, applied after the exposure.
vec3 aces_narkowicz(vec3 x) {
  return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Blue -> cyan -> green -> yellow -> red, t in [0, 1].
vec3 heat(float t) {
  t = clamp(t, 0.0, 1.0);
  return clamp(vec3(1.5 - abs(4.0 * t - 3.0),
                    1.5 - abs(4.0 * t - 2.0),
                    1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0);
}

void main() {
  vec3 mean = spp > 0.0 ? texture(sums, uv).rgb / spp : vec3(0.0);
  if (mode == 1) {
    // Standard error of the pixel mean over the mean, log scale: 0.1% blue,
    // 100% red. Black where the pixel has no light to measure against.
    float m = dot(mean, lum_weights);
    float var = max(texture(sums_sq, uv).r / max(spp, 1.0) - m * m, 0.0);
    float rel = sqrt(var / max(spp - 1.0, 1.0)) / m;  // sample variance / n
    colour = vec4(m > 0.0 ? heat((log(rel) / log(10.0) + 3.0) / 3.0) : vec3(0.0), 1.0);
    return;
  }
  // SCENES.md: 8-bit value = min(255, L^(1/2.2)) = 255 * min(1, (L / 255^2.2)^(1/2.2)),
  // truncated like the report's (and the PNG writer's) integer conversion;
  // GL would round, which shows as a half-level brightening against the PNG.
  vec3 x = max(mean * exposure, 0.0);
  if (tonemap == 1) x = aces_narkowicz(x);
  vec3 v = min(pow(x, vec3(1.0 / gamma)), 1.0);
  colour = vec4(floor(v * 255.0) / 255.0, 1.0);
}
