// SPDX-License-Identifier: MIT
// Random numbers and direction sampling for the reference path tracer (CPU-tested, docs/style.md §8). Requires
// phase.glsl (and shaders/shared/reference_params.h for the REFERENCE_PHASE_* selectors).
// Sources: O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for
// Random Number Generation" (the RXS-M-XS 32-bit output, as in Jarzynski & Olano 2020, "Hash Functions
// for GPU Rendering"); the inverse CDF of Henyey-Greenstein (e.g. Pharr, Jakob & Humphreys, PBRT 3rd ed.,
// 15.2.3); Duff et al. 2017, "Building an Orthonormal Basis, Revisited".

// One PCG step: a well-mixed 32-bit hash of v.
uint pcgHash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform float in [0, 1) from the generator state, which it advances: PCG's linear congruential step
// (period 2^32) and its RXS-M-XS output. (Hashing the state again instead would walk a random mapping,
// whose cycles are ~1e5 long: a path's samples would repeat.)
float randomFloat(INOUT(uint) state)
{
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0f / 16777216.0f);
}

// Cosine of the scattering angle drawn from Henyey-Greenstein(g) with the uniform number u in [0, 1).
float sampleHenyeyGreensteinCos(float g, float u)
{
    if (abs(g) < 1e-3f)
        return 1.0f - 2.0f * u;
    float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

// Draine(g, alpha) is HG(g) times (1 + alpha nu^2) / const: HG samples kept with probability
// (1 + alpha nu^2) / (1 + alpha). The mean acceptance is (1 + alpha (1 + 2 g^2) / 3) / (1 + alpha), above
// 0.35 for the droplet fits (alpha < 30, g > 0.3); after 32 refusals (probability < 1e-14) it keeps the last.
float sampleDraineCos(float g, float alpha, INOUT(uint) rng)
{
    float nu = 1.0f;
    for (int i = 0; i < 32; ++i)
    {
        nu = sampleHenyeyGreensteinCos(g, randomFloat(rng));
        if (randomFloat(rng) * (1.0f + alpha) <= 1.0f + alpha * nu * nu)
            break;
    }
    return nu;
}

// The phase function the reference scatters with (REFERENCE_PHASE_*): twoLobe = (forward g, back g, forward
// weight) of the model's phaseTwoLobeHG, dropletUm the droplet diameter of phaseHgDraine.
float referencePhase(int model, vec3 twoLobe, float dropletUm, float nu)
{
    if (model == REFERENCE_PHASE_ISOTROPIC)
        return phaseIsotropic();
    if (model == REFERENCE_PHASE_HG_DRAINE)
        return phaseHgDraine(dropletUm, nu);
    return phaseTwoLobeHG(twoLobe.x, twoLobe.y, twoLobe.z, nu);
}

// A scattering-angle cosine drawn exactly from referencePhase (the path weight stays the albedo).
float sampleReferencePhaseCos(int model, vec3 twoLobe, float dropletUm, INOUT(uint) rng)
{
    float pick = randomFloat(rng);
    if (model == REFERENCE_PHASE_ISOTROPIC)
        return 1.0f - 2.0f * randomFloat(rng);
    if (model == REFERENCE_PHASE_HG_DRAINE)
    {
        vec4 q = hgDraineParams(dropletUm);
        if (pick >= q.w)
            return sampleHenyeyGreensteinCos(q.x, randomFloat(rng));
        return sampleDraineCos(q.y, q.z, rng);
    }
    return sampleHenyeyGreensteinCos(pick < twoLobe.z ? twoLobe.x : twoLobe.y, randomFloat(rng));
}

// The unit direction at angle acos(cosTheta) from the unit `axis`, at azimuth phi (rad) about it.
vec3 directionAround(vec3 axis, float cosTheta, float phi)
{
    float sign = axis.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + axis.z);
    float b = axis.x * axis.y * a;
    vec3 t = vec3(1.0f + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
    vec3 s = vec3(b, sign + axis.y * axis.y * a, -axis.y);
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    return normalize(t * (sinTheta * cos(phi)) + s * (sinTheta * sin(phi)) + axis * cosTheta);
}

// A cosine-distributed direction about the unit `normal` (pdf cos / pi) from two uniform numbers.
vec3 sampleCosineDirection(vec3 normal, float u1, float u2)
{
    return directionAround(normal, sqrt(u1), 2.0f * SKY_PI * u2);
}
