/* glTF node transforms at a time (see gltf_pose.h). */
#include "scene/gltf_pose.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bool gltf_pose_init(struct gltf_pose *pose, const struct gltf_scene *scene, struct error *err)
{
    memset(pose, 0, sizeof *pose);
    size_t n = scene->node_count > 0 ? (size_t)scene->node_count : 1;
    pose->translation = malloc(n * sizeof *pose->translation);
    pose->rotation = malloc(n * sizeof *pose->rotation);
    pose->scale = malloc(n * sizeof *pose->scale);
    pose->driven = malloc(n * sizeof *pose->driven);
    pose->weights = malloc(n * sizeof *pose->weights);
    pose->world = malloc(n * sizeof *pose->world);
    pose->composed = malloc(n * sizeof *pose->composed);
    if (!pose->translation || !pose->rotation || !pose->scale || !pose->driven || !pose->weights || !pose->world ||
        !pose->composed) {
        gltf_pose_free(pose);
        return error_set(err, "glTF: out of memory for the pose of %d nodes", scene->node_count);
    }
    pose->node_count = scene->node_count;
    gltf_pose_at(pose, scene, -1, 0.0);
    return true;
}

void gltf_pose_free(struct gltf_pose *pose)
{
    free(pose->translation);
    free(pose->rotation);
    free(pose->scale);
    free(pose->driven);
    free(pose->weights);
    free(pose->world);
    free(pose->composed);
    memset(pose, 0, sizeof *pose);
}

/* The spherical interpolation of unit quaternions a and b (the shorter
 * way round), falling back to a normalised lerp where they nearly agree. */
static void slerp(const float *a, const float *b, float u, float *out)
{
    double d = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2] + (double)a[3] * b[3];
    double sign = d < 0 ? -1.0 : 1.0;
    d = fabs(d);
    double wa = 1.0 - u, wb = u;
    if (d < 0.9995) {
        double theta = acos(d), s = sin(theta);
        wa = sin((1.0 - u) * theta) / s;
        wb = sin(u * theta) / s;
    }
    double q[4], len = 0;
    for (int k = 0; k < 4; k++) {
        q[k] = wa * a[k] + wb * sign * b[k];
        len += q[k] * q[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 4; k++)
        out[k] = len > 1e-30 ? (float)(q[k] / len) : (k == 3 ? 1.0f : 0.0f);
}

static void normalise4(float *q)
{
    double len = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] + (double)q[3] * q[3]);
    if (len > 1e-30)
        for (int k = 0; k < 4; k++)
            q[k] = (float)(q[k] / len);
    else
        q[0] = q[1] = q[2] = 0, q[3] = 1;
}

void gltf_channel_sample(const struct gltf_channel *c, double t, float *out)
{
    int n = c->components;
    bool cubic = c->interpolation == GLTF_CUBICSPLINE;
    size_t stride = (size_t)n * (cubic ? 3 : 1), at = cubic ? (size_t)n : 0; /* a cubic key: in, value, out */
    size_t last = c->key_count - 1;
    if (!(t > c->times[0]) || c->key_count == 1) {
        memcpy(out, c->values + at, (size_t)n * sizeof *out);
    } else if (t >= c->times[last]) {
        memcpy(out, c->values + last * stride + at, (size_t)n * sizeof *out);
    } else {
        /* the key k with times[k] <= t < times[k + 1] */
        size_t lo = 0, hi = last;
        while (hi - lo > 1) {
            size_t mid = (lo + hi) / 2;
            if (c->times[mid] <= t)
                lo = mid;
            else
                hi = mid;
        }
        double td = (double)c->times[hi] - c->times[lo];
        double u = td > 0 ? (t - c->times[lo]) / td : 0.0;
        const float *k0 = c->values + lo * stride, *k1 = c->values + hi * stride;
        if (c->interpolation == GLTF_STEP || td <= 0) {
            memcpy(out, k0 + at, (size_t)n * sizeof *out);
        } else if (!cubic) {
            if (c->path == GLTF_PATH_ROTATION)
                slerp(k0, k1, (float)u, out);
            else
                for (int i = 0; i < n; i++)
                    out[i] = (float)(k0[i] + (k1[i] - k0[i]) * u);
        } else {
            /* Appendix C: the Hermite spline through v_k, v_k+1 with the
             * tangents b_k (k's out) and a_k+1 (k+1's in), scaled by td */
            double u2 = u * u, u3 = u2 * u;
            double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            for (int i = 0; i < n; i++)
                out[i] = (float)(h00 * k0[n + i] + h10 * td * k0[2 * n + i] + h01 * k1[n + i] + h11 * td * k1[i]);
        }
    }
    if (c->path == GLTF_PATH_ROTATION)
        normalise4(out);
}

void gltf_pose_at(struct gltf_pose *pose, const struct gltf_scene *scene, int animation, double t)
{
    for (int i = 0; i < scene->node_count; i++) {
        const struct gltf_node *g = &scene->nodes[i];
        if (g->has_matrix) {
            /* glTF animates TRS nodes only; a file that drives a matrix
             * node moves it from its matrix's decomposition */
            mat4 m;
            memcpy(m.m, g->matrix, sizeof m.m);
            gltf_pose_decompose(m, &pose->translation[i], &pose->rotation[i], &pose->scale[i]);
        } else {
            pose->translation[i] = vec3_make(g->translation[0], g->translation[1], g->translation[2]);
            pose->rotation[i] = (quat){g->rotation[0], g->rotation[1], g->rotation[2], g->rotation[3]};
            pose->scale[i] = vec3_make(g->scale[0], g->scale[1], g->scale[2]);
        }
        pose->driven[i] = false;
        memcpy(pose->weights[i], g->weights, sizeof pose->weights[i]);
    }
    if (animation >= 0 && animation < scene->animation_count) {
        const struct gltf_animation *a = &scene->animations[animation];
        for (int k = 0; k < a->channel_count; k++) {
            const struct gltf_channel *c = &a->channels[k];
            float v[GLTF_MAX_WEIGHTS > 4 ? GLTF_MAX_WEIGHTS : 4];
            gltf_channel_sample(c, t, v);
            int i = c->node;
            if (c->path == GLTF_PATH_WEIGHTS) {
                memcpy(pose->weights[i], v, (size_t)c->components * sizeof *v);
                continue;
            }
            pose->driven[i] = true;
            if (c->path == GLTF_PATH_TRANSLATION)
                pose->translation[i] = vec3_make(v[0], v[1], v[2]);
            else if (c->path == GLTF_PATH_ROTATION)
                pose->rotation[i] = (quat){v[0], v[1], v[2], v[3]};
            else
                pose->scale[i] = vec3_make(v[0], v[1], v[2]);
        }
    }
    /* parents before children: a node's world waits for its parent's
     * (gltf_file_scene refused cycles and trees deeper than 256) */
    bool *done = pose->composed;
    memset(done, 0, (size_t)scene->node_count * sizeof *done);
    for (int i = 0; i < scene->node_count; i++) {
        int chain[258], len = 0;
        for (int j = i; j >= 0 && !done[j] && len < 258; j = scene->nodes[j].parent)
            chain[len++] = j;
        while (len > 0) {
            int j = chain[--len];
            const struct gltf_node *g = &scene->nodes[j];
            mat4 local;
            if (g->has_matrix && !pose->driven[j])
                memcpy(local.m, g->matrix, sizeof local.m);
            else
                local = mat4_trs(pose->translation[j], pose->rotation[j], pose->scale[j]);
            pose->world[j] = g->parent >= 0 ? mat4_mul(pose->world[g->parent], local) : local;
            done[j] = true;
        }
    }
}

void gltf_pose_decompose(mat4 m, vec3 *position, quat *rotation, vec3 *scale)
{
    const float *a = m.m;
    *position = vec3_make(a[12], a[13], a[14]);
    double sx = sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2]);
    double sy = sqrt((double)a[4] * a[4] + (double)a[5] * a[5] + (double)a[6] * a[6]);
    double sz = sqrt((double)a[8] * a[8] + (double)a[9] * a[9] + (double)a[10] * a[10]);
    double det = a[0] * ((double)a[5] * a[10] - (double)a[9] * a[6]) - a[4] * ((double)a[1] * a[10] - (double)a[9] * a[2]) +
                 a[8] * ((double)a[1] * a[6] - (double)a[5] * a[2]);
    if (det < 0)
        sx = -sx;
    *scale = vec3_make((float)sx, (float)sy, (float)sz);
    *rotation = quat_identity();
    if (!(fabs(sx) > 1e-30 && sy > 1e-30 && sz > 1e-30))
        return;
    double r[9] = {a[0] / sx, a[1] / sx, a[2] / sx, a[4] / sy, a[5] / sy, a[6] / sy, a[8] / sz, a[9] / sz, a[10] / sz};
    double tr = r[0] + r[4] + r[8], x, y, z, w;
    if (tr > 0) {
        double k = 0.5 / sqrt(tr + 1.0);
        w = 0.25 / k, x = (r[5] - r[7]) * k, y = (r[6] - r[2]) * k, z = (r[1] - r[3]) * k;
    } else if (r[0] > r[4] && r[0] > r[8]) {
        double k = 2.0 * sqrt(1.0 + r[0] - r[4] - r[8]);
        w = (r[5] - r[7]) / k, x = 0.25 * k, y = (r[3] + r[1]) / k, z = (r[6] + r[2]) / k;
    } else if (r[4] > r[8]) {
        double k = 2.0 * sqrt(1.0 + r[4] - r[0] - r[8]);
        w = (r[6] - r[2]) / k, x = (r[3] + r[1]) / k, y = 0.25 * k, z = (r[7] + r[5]) / k;
    } else {
        double k = 2.0 * sqrt(1.0 + r[8] - r[0] - r[4]);
        w = (r[1] - r[3]) / k, x = (r[6] + r[2]) / k, y = (r[7] + r[5]) / k, z = 0.25 * k;
    }
    float q[4] = {(float)x, (float)y, (float)z, (float)w};
    normalise4(q);
    *rotation = (quat){q[0], q[1], q[2], q[3]};
}

void gltf_pose_joint_matrices(const struct gltf_pose *pose, const struct gltf_scene *scene, int skin, float *out)
{
    const struct gltf_skin *k = &scene->skins[skin];
    for (int j = 0; j < k->joint_count; j++) {
        mat4 ibm;
        memcpy(ibm.m, k->inverse_bind + (size_t)j * 16, sizeof ibm.m);
        mat4 m = mat4_mul(pose->world[k->joints[j]], ibm);
        memcpy(out + (size_t)j * 16, m.m, sizeof m.m);
    }
}
