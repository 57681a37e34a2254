// SPDX-License-Identifier: MIT
// Cloud phase functions, each normalised to integrate to 1 over the sphere (CPU-tested, docs/style.md §8).
// nu is the cosine of the scattering angle (1 = straight on, the light continuing forward).
// Sources: Henyey & Greenstein 1941; two lobes as in Schneider 2015 and Hillaire 2016; Draine 2003
// ("Scattering by Interstellar Dust Grains"); Jendersie & d'Eon 2023, "An Approximate Mie Scattering
// Function for Fog and Cloud Rendering" (SIGGRAPH talk), whose fits give the HG + Draine blend from
// the droplet diameter.

#ifndef SKY_PI
#define SKY_PI 3.14159265358979f
#endif

// Henyey-Greenstein, g in (-1, 1): mean cosine g.
float phaseHenyeyGreenstein(float g, float nu)
{
    float g2 = g * g;
    float denom = max(1.0f + g2 - 2.0f * g * nu, 1e-6f);
    return (1.0f - g2) / (4.0f * SKY_PI * denom * sqrt(denom));
}

// Two HG lobes: forwardWeight * HG(gForward) + (1 - forwardWeight) * HG(gBack). Mean cosine:
// forwardWeight * gForward + (1 - forwardWeight) * gBack. The published values are gForward ~0.8, gBack ~-0.3.
float phaseTwoLobeHG(float gForward, float gBack, float forwardWeight, float nu)
{
    return mix(phaseHenyeyGreenstein(gBack, nu), phaseHenyeyGreenstein(gForward, nu), forwardWeight);
}

// Draine's phase function: HG times (1 + alpha nu^2), normalised by 1 + alpha (1 + 2 g^2) / 3.
float phaseDraine(float g, float alpha, float nu)
{
    float g2 = g * g;
    float denom = max(1.0f + g2 - 2.0f * g * nu, 1e-6f);
    return (1.0f - g2) * (1.0f + alpha * nu * nu) /
           (4.0f * SKY_PI * denom * sqrt(denom) * (1.0f + alpha * (1.0f + 2.0f * g2) / 3.0f));
}

// Jendersie & d'Eon fit parameters for water droplets of diameter dUm (micrometres), clamped to the
// fitted range [1.5, 50]: x = g of the HG lobe, y = g of the Draine lobe, z = Draine alpha, w = weight
// of the Draine lobe.
vec4 hgDraineParams(float dUm)
{
    float d = clamp(dUm, 1.5f, 50.0f);
    if (d >= 5.0f)
    {
        return vec4(exp(-0.0990567f / (d - 1.67154f)), exp(-2.20679f / (d + 3.91029f) - 0.428934f),
                    exp(3.62489f - 8.29288f / (d + 5.52825f)), exp(-0.599085f / (d - 0.641583f) - 0.665888f));
    }
    float logD = log(d);
    float logLogD = log(logD);
    return vec4(0.0604931f * logLogD + 0.940256f, 0.500411f - 0.081287f / (-2.0f * logD + tan(logD) + 1.27551f),
                7.30354f * logD + 6.31675f,
                0.026914f * (logD - cos(5.68947f * (logLogD - 0.0292149f))) + 0.376475f);
}

// The approximate Mie phase of a cloud of droplets of diameter dUm (micrometres): (1 - wD) HG + wD Draine.
// Typical cumulus droplets are 10-20 um; 20 um gives a forward peak with mean cosine ~0.86.
float phaseHgDraine(float dUm, float nu)
{
    vec4 q = hgDraineParams(dUm);
    return mix(phaseHenyeyGreenstein(q.x, nu), phaseDraine(q.y, q.z, nu), q.w);
}

// Uniform phase 1 / (4 pi), for the multiple-scattering approximations.
float phaseIsotropic()
{
    return 1.0f / (4.0f * SKY_PI);
}
