// SPDX-License-Identifier: MIT
// Seeded, tileable cloud noise (docs/model.md): integer hash, gradient (Perlin) noise, cellular (Worley) noise,
// their FBM sums, Schneider's Perlin-Worley, and 2D curl noise; plus the per-texel recipes of the three
// noise textures, so that the compute passes and the CPU tests run the same code.
// Include shaders/shared/noise_params.h first.
//
// Conventions: a lattice noise takes a position p in lattice units and an integer period (cells); it is
// periodic in p with that period along every axis. The FBM and texel functions take texture coordinates
// (uvw in [0,1) per tile) and are periodic with period 1, so every octave tiles with the texture.
// Keys (uvec3) select an independent noise: noiseSeedKey(seed, salt) mixes the user seed with a salt
// that names the function and octave.
//
// Sources: Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3) 2020 (PCG3D);
// Perlin, "Improving Noise", SIGGRAPH 2002 (quintic fade, 12 edge gradients); Worley, "A Cellular
// Texture Basis Function", SIGGRAPH 1996 (F1); Schneider, "Real-Time Volumetric Cloudscapes", GPU Pro 7
// 2016 (Perlin-Worley, Worley FBM weights 0.625/0.25/0.125); Bridson et al., "Curl-Noise for Procedural
// Fluid Flow", SIGGRAPH 2007 (curl of a scalar potential is divergence-free).

// PCG3D of Jarzynski & Olano 2020: an LCG step then two rounds of cross-component multiplies.
uvec3 noisePcg3(uvec3 v)
{
    v = v * 1664525u + uvec3(1013904223u);
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v = v ^ (v >> 16u);
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

// Key of one noise function: decorrelated for every (seed, salt) pair.
uvec3 noiseSeedKey(uint seed, uint salt)
{
    return noisePcg3(uvec3(seed, salt, 0x9E3779B9u));
}

// The top 24 bits of a hash as a float in [0, 1) (exact: 24 bits fit a float mantissa).
float noiseUnitFloat(uint h)
{
    return float(h >> 8u) * 5.96046448e-8f;  // 2^-24
}

// Wraps a lattice index into [0, period); valid for c in [-period, 2 period).
int noiseWrapIndex(int c, int period)
{
    return c < 0 ? c + period : (c >= period ? c - period : c);
}

// Hash of lattice cell (x, y, z), already wrapped into [0, period).
uvec3 noiseHashCell(int x, int y, int z, uvec3 key)
{
    return noisePcg3(uvec3(uint(x), uint(y), uint(z)) + key);
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 (C2 across cells) and its derivative.
float noiseFade(float t)
{
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float noiseFadeDerivative(float t)
{
    return 30.0f * t * t * (t * (t - 2.0f) + 1.0f);
}

// Dot product of offset d with one of Perlin's 12 cube-edge gradients (2002), picked by 4 hash bits.
float noisePerlinGradDot(uint h, vec3 d)
{
    uint b = h >> 28u;
    float u = b < 8u ? d.x : d.y;
    float v = b < 4u ? d.y : ((b == 12u || b == 14u) ? d.x : d.z);
    return ((b & 1u) == 0u ? u : -u) + ((b & 2u) == 0u ? v : -v);
}

// 3D gradient noise, about [-1, 1], periodic in p with `period` cells (period >= 1).
float perlinNoise3(vec3 p, int period, uvec3 key)
{
    SKY_ASSERT(period >= 1);
    float periodF = float(period);
    vec3 q = p - periodF * floor(p / periodF);
    vec3 cellF = floor(q);
    vec3 f = q - cellF;
    int x0 = noiseWrapIndex(int(cellF.x), period);
    int y0 = noiseWrapIndex(int(cellF.y), period);
    int z0 = noiseWrapIndex(int(cellF.z), period);
    int x1 = noiseWrapIndex(x0 + 1, period);
    int y1 = noiseWrapIndex(y0 + 1, period);
    int z1 = noiseWrapIndex(z0 + 1, period);

    float n000 = noisePerlinGradDot(noiseHashCell(x0, y0, z0, key).x, f);
    float n100 = noisePerlinGradDot(noiseHashCell(x1, y0, z0, key).x, f - vec3(1.0f, 0.0f, 0.0f));
    float n010 = noisePerlinGradDot(noiseHashCell(x0, y1, z0, key).x, f - vec3(0.0f, 1.0f, 0.0f));
    float n110 = noisePerlinGradDot(noiseHashCell(x1, y1, z0, key).x, f - vec3(1.0f, 1.0f, 0.0f));
    float n001 = noisePerlinGradDot(noiseHashCell(x0, y0, z1, key).x, f - vec3(0.0f, 0.0f, 1.0f));
    float n101 = noisePerlinGradDot(noiseHashCell(x1, y0, z1, key).x, f - vec3(1.0f, 0.0f, 1.0f));
    float n011 = noisePerlinGradDot(noiseHashCell(x0, y1, z1, key).x, f - vec3(0.0f, 1.0f, 1.0f));
    float n111 = noisePerlinGradDot(noiseHashCell(x1, y1, z1, key).x, f - vec3(1.0f, 1.0f, 1.0f));

    float ux = noiseFade(f.x);
    float uy = noiseFade(f.y);
    float uz = noiseFade(f.z);
    float nx00 = mix(n000, n100, ux);
    float nx10 = mix(n010, n110, ux);
    float nx01 = mix(n001, n101, ux);
    float nx11 = mix(n011, n111, ux);
    return mix(mix(nx00, nx10, uy), mix(nx01, nx11, uy), uz);
}

// Worley F1 turned into billows: 1 - (distance to the nearest feature point, lattice units), clamped to
// [0, 1]; 1 on a feature point. One feature point per cell; the 27 cells around p are searched because
// a jittered point anywhere in a neighbour can be the nearest. Periodic in p with `period` cells.
float worleyNoise3(vec3 p, int period, uvec3 key)
{
    SKY_ASSERT(period >= 1);
    float periodF = float(period);
    vec3 q = p - periodF * floor(p / periodF);
    vec3 cellF = floor(q);
    vec3 f = q - cellF;
    int cx = int(cellF.x);
    int cy = int(cellF.y);
    int cz = int(cellF.z);
    float nearest2 = 3.0f;  // a feature point of the own cell is within sqrt(3)
    for (int dz = -1; dz <= 1; ++dz)
    {
        int z = noiseWrapIndex(cz + dz, period);
        for (int dy = -1; dy <= 1; ++dy)
        {
            int y = noiseWrapIndex(cy + dy, period);
            for (int dx = -1; dx <= 1; ++dx)
            {
                uvec3 h = noiseHashCell(noiseWrapIndex(cx + dx, period), y, z, key);
                vec3 d = vec3(float(dx) + noiseUnitFloat(h.x), float(dy) + noiseUnitFloat(h.y),
                              float(dz) + noiseUnitFloat(h.z)) - f;
                nearest2 = min(nearest2, dot(d, d));
            }
        }
    }
    return 1.0f - min(sqrt(nearest2), 1.0f);
}

// One Worley octave of `period` cells per tile at texture coordinate uvw. The key depends on the period,
// so channels that share an octave share its values (and a pass can compute each octave once).
float worleyOctave(vec3 uvw, int period, uint seed, uint salt)
{
    return worleyNoise3(uvw * float(period), period, noiseSeedKey(seed, salt + uint(period)));
}

// Schneider's 3-octave Worley FBM weights; w0 is the lowest frequency. Result in [0, 1].
float worleyFbmCombine(float w0, float w1, float w2)
{
    return w0 * 0.625f + w1 * 0.25f + w2 * 0.125f;
}

// Worley FBM of octaves period, 2 period, 4 period at texture coordinate uvw; in [0, 1], periodic in uvw.
float worleyFbm3(vec3 uvw, int period, uint seed, uint salt)
{
    return worleyFbmCombine(worleyOctave(uvw, period, seed, salt), worleyOctave(uvw, period * 2, seed, salt),
                            worleyOctave(uvw, period * 4, seed, salt));
}

// Perlin FBM (gain 0.5, lacunarity 2) at texture coordinate uvw, mapped from about [-1, 1] to [0, 1].
float perlinFbm3(vec3 uvw, int period, int octaves, uint seed)
{
    float sum = 0.0f;
    float amplitude = 1.0f;
    float amplitudeSum = 0.0f;
    int octavePeriod = period;
    for (int i = 0; i < octaves; ++i)
    {
        uvec3 key = noiseSeedKey(seed, NOISE_SALT_PERLIN + uint(octavePeriod));
        sum += amplitude * perlinNoise3(uvw * float(octavePeriod), octavePeriod, key);
        amplitudeSum += amplitude;
        amplitude *= 0.5f;
        octavePeriod *= 2;
    }
    return clamp(0.5f + 0.5f * sum / amplitudeSum, 0.0f, 1.0f);
}

// Schneider's remap (GPU Pro 7): maps v from [lo0, hi0] to [lo1, hi1], unclamped.
float noiseRemap(float v, float lo0, float hi0, float lo1, float hi1)
{
    return lo1 + (v - lo0) * (hi1 - lo1) / (hi0 - lo0);
}

// Perlin-Worley (Schneider 2016): Perlin noise dilated by billowy Worley noise, remap(perlin, 0, 1,
// worley, 1) = worley + perlin (1 - worley). Where the Worley FBM is high (cell centres) the value rises
// to 1, so the connected Perlin shapes gain rounded, billowy edges. Inputs and result in [0, 1].
float perlinWorley(float perlin01, float worleyFbm)
{
    return clamp(noiseRemap(perlin01, 0.0f, 1.0f, worleyFbm, 1.0f), 0.0f, 1.0f);
}

// 2D gradient noise with its analytic gradient: (value, d/dx, d/dy) in lattice units, value about
// [-0.7, 0.7]; periodic in p with `period` cells. Gradients are unit vectors at hashed angles.
vec3 gradientNoise2(vec2 p, int period, uvec3 key)
{
    SKY_ASSERT(period >= 1);
    float periodF = float(period);
    vec2 q = p - periodF * floor(p / periodF);
    vec2 cellF = floor(q);
    vec2 f = q - cellF;
    int x0 = noiseWrapIndex(int(cellF.x), period);
    int y0 = noiseWrapIndex(int(cellF.y), period);
    int x1 = noiseWrapIndex(x0 + 1, period);
    int y1 = noiseWrapIndex(y0 + 1, period);

    const float twoPi = 6.28318530718f;
    float angleA = twoPi * noiseUnitFloat(noiseHashCell(x0, y0, 0, key).x);
    float angleB = twoPi * noiseUnitFloat(noiseHashCell(x1, y0, 0, key).x);
    float angleC = twoPi * noiseUnitFloat(noiseHashCell(x0, y1, 0, key).x);
    float angleD = twoPi * noiseUnitFloat(noiseHashCell(x1, y1, 0, key).x);
    vec2 ga = vec2(cos(angleA), sin(angleA));
    vec2 gb = vec2(cos(angleB), sin(angleB));
    vec2 gc = vec2(cos(angleC), sin(angleC));
    vec2 gd = vec2(cos(angleD), sin(angleD));

    float a = dot(ga, f);
    float b = dot(gb, f - vec2(1.0f, 0.0f));
    float c = dot(gc, f - vec2(0.0f, 1.0f));
    float d = dot(gd, f - vec2(1.0f, 1.0f));
    float ux = noiseFade(f.x);
    float uy = noiseFade(f.y);
    float k = a - b - c + d;
    float value = a + (b - a) * ux + (c - a) * uy + k * ux * uy;
    vec2 gradient = ga + (gb - ga) * ux + (gc - ga) * uy + (ga - gb - gc + gd) * (ux * uy) +
                    vec2(noiseFadeDerivative(f.x) * ((b - a) + k * uy), noiseFadeDerivative(f.y) * ((c - a) + k * ux));
    return vec3(value, gradient.x, gradient.y);
}

// Scale that brings the curl of the normalised potential below to about [-1, 1] (measured by
// tests/unit/test_noise.cpp: 99.9% of texels inside, for the texture's period and octaves).
#define CURL_NOISE_GAIN 0.5f

// Curl of a tileable FBM potential psi(uv) = sum_i 0.5^i n(uv * period 2^i): (d psi/dv, -d psi/du),
// divergence-free (Bridson 2007) and periodic in uv with period 1. Derivatives are taken per lowest-
// octave cell and scaled by CURL_NOISE_GAIN, so the result is about [-1, 1].
vec2 curlNoise2(vec2 uv, int period, int octaves, uint seed)
{
    vec2 gradient = vec2(0.0f);
    float amplitude = 1.0f;
    float amplitudeSum = 0.0f;
    int octavePeriod = period;
    for (int i = 0; i < octaves; ++i)
    {
        uvec3 key = noiseSeedKey(seed, NOISE_SALT_CURL + uint(octavePeriod));
        vec3 n = gradientNoise2(uv * float(octavePeriod), octavePeriod, key);
        // chain rule: d/duv n(uv * P) = P n'; expressed per lowest-octave cell: P / period
        float scale = amplitude * float(octavePeriod) / float(period);
        gradient += vec2(n.y, n.z) * scale;
        amplitudeSum += amplitude;
        amplitude *= 0.5f;
        octavePeriod *= 2;
    }
    gradient *= CURL_NOISE_GAIN / amplitudeSum;
    return vec2(gradient.y, -gradient.x);
}

// ---- Per-texel recipes of the noise textures (noise_params.h lists the channels) ----

// Texture coordinate of a texel centre: tiles with period 1, so texel sizeTexels wraps onto texel 0.
vec3 noiseTexelCoord3(uvec3 texel, uint sizeTexels)
{
    return (vec3(texel) + vec3(0.5f)) / float(sizeTexels);
}

// Base texture: R = Perlin-Worley, G,B,A = Worley FBM starting at 1x, 2x, 4x BASE_NOISE_WORLEY_PERIOD.
// Five distinct Worley octaves (periods 4..64) serve all four channels.
vec4 baseNoiseTexel(uvec3 texel, uint sizeTexels, uint seed)
{
    vec3 uvw = noiseTexelCoord3(texel, sizeTexels);
    int period = BASE_NOISE_WORLEY_PERIOD;
    float w0 = worleyOctave(uvw, period, seed, NOISE_SALT_WORLEY);
    float w1 = worleyOctave(uvw, period * 2, seed, NOISE_SALT_WORLEY);
    float w2 = worleyOctave(uvw, period * 4, seed, NOISE_SALT_WORLEY);
    float w3 = worleyOctave(uvw, period * 8, seed, NOISE_SALT_WORLEY);
    float w4 = worleyOctave(uvw, period * 16, seed, NOISE_SALT_WORLEY);
    float lowFbm = worleyFbmCombine(w0, w1, w2);
    float perlin = perlinFbm3(uvw, BASE_NOISE_PERLIN_PERIOD, BASE_NOISE_PERLIN_OCTAVES, seed);
    return vec4(perlinWorley(perlin, lowFbm), lowFbm, worleyFbmCombine(w1, w2, w3), worleyFbmCombine(w2, w3, w4));
}

// Detail texture: R,G,B = Worley FBM starting at 1x, 2x, 4x DETAIL_NOISE_WORLEY_PERIOD; A = the three
// combined with the same 0.625/0.25/0.125 weights (Schneider's high-frequency FBM), all in [0, 1].
vec4 detailNoiseTexel(uvec3 texel, uint sizeTexels, uint seed)
{
    vec3 uvw = noiseTexelCoord3(texel, sizeTexels);
    int period = DETAIL_NOISE_WORLEY_PERIOD;
    float w0 = worleyOctave(uvw, period, seed, NOISE_SALT_DETAIL);
    float w1 = worleyOctave(uvw, period * 2, seed, NOISE_SALT_DETAIL);
    float w2 = worleyOctave(uvw, period * 4, seed, NOISE_SALT_DETAIL);
    float w3 = worleyOctave(uvw, period * 8, seed, NOISE_SALT_DETAIL);
    float w4 = worleyOctave(uvw, period * 16, seed, NOISE_SALT_DETAIL);
    float r = worleyFbmCombine(w0, w1, w2);
    float g = worleyFbmCombine(w1, w2, w3);
    float b = worleyFbmCombine(w2, w3, w4);
    return vec4(r, g, b, worleyFbmCombine(r, g, b));
}

// Curl texture: xy = curl vector (about [-1, 1]), zw = 0.
vec4 curlNoiseTexel(uvec2 texel, uint sizeTexels, uint seed)
{
    vec2 uv = (vec2(texel) + vec2(0.5f)) / float(sizeTexels);
    vec2 curl = curlNoise2(uv, CURL_NOISE_PERIOD, CURL_NOISE_OCTAVES, seed);
    return vec4(curl.x, curl.y, 0.0f, 0.0f);
}
