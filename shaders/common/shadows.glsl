// The shadow maps a pass reads (src/passes/shadow_inputs.c binds them):
// up to 4, 2D (directional and spot lights) or distance cube maps (point
// and linear lights), each covering a run of the frame's light entries.
uniform int u_shadow_total;
uniform int u_shadow_first[4];
uniform int u_shadow_count[4];
uniform int u_shadow_cube[4];
uniform mat4 u_shadow_matrix[4];
uniform vec4 u_shadow_params[4]; // range, bias, 1/size
uniform sampler2D u_shadow_2d[4];
uniform samplerCube u_shadow_cubes[4];

// Fraction of light reaching p from the light of shadow map k (3x3 PCF).
float shadow_visibility(int k, vec3 p, vec3 n, vec3 to_light)
{
    float bias = u_shadow_params[k].y * (1.0 + 2.0 * (1.0 - abs(dot(n, to_light))));
    if (u_shadow_cube[k] == 1) {
        vec3 d = (u_shadow_matrix[k] * vec4(p, 1.0)).xyz; // p - light position
        float dist = length(d);
        float stored = texture(u_shadow_cubes[k], d).r * u_shadow_params[k].x;
        return dist - bias > stored ? 0.0 : 1.0;
    }
    vec4 c = u_shadow_matrix[k] * vec4(p + n * bias, 1.0);
    if (c.w <= 0.0)
        return 1.0;
    vec3 q = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))))
        return 1.0;
    q.z = min(q.z, 1.0); // past the far plane: behind whatever the map holds there
    float texel = u_shadow_params[k].z, lit = 0.0;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++)
            lit += q.z - 1e-5 > texture(u_shadow_2d[k], q.xy + vec2(x, y) * texel).r ? 0.0 : 1.0;
    return lit / 9.0;
}

float visibility(int light, vec3 p, vec3 n, vec3 to_light)
{
    for (int k = 0; k < u_shadow_total; k++)
        if (light >= u_shadow_first[k] && light < u_shadow_first[k] + u_shadow_count[k])
            return shadow_visibility(k, p, n, to_light);
    return 1.0;
}
