// The project's only C++: a thin shim with a C interface over tinygltf
// (Debian's libtinygltf). It flattens the default scene into one triangle
// mesh and validates what it reads: out-of-range indices, non-finite
// positions and truncated buffers are errors naming the file.
#include "io/gltf.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace {

struct Fail {
    std::string message;
};

using Mat = std::array<double, 16>; // column-major

Mat mat_identity()
{
    Mat m{};
    m[0] = m[5] = m[10] = m[15] = 1.0;
    return m;
}

Mat mat_mul(const Mat &a, const Mat &b)
{
    Mat r{};
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    return r;
}

Mat node_matrix(const tinygltf::Node &node)
{
    if (node.matrix.size() == 16) {
        Mat m{};
        for (int i = 0; i < 16; i++)
            m[i] = node.matrix[i];
        return m;
    }
    Mat t = mat_identity(), r = mat_identity(), s = mat_identity();
    if (node.translation.size() == 3) {
        t[12] = node.translation[0];
        t[13] = node.translation[1];
        t[14] = node.translation[2];
    }
    if (node.rotation.size() == 4) {
        double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
        double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (len > 1e-20) {
            x /= len; y /= len; z /= len; w /= len;
        } else {
            x = y = z = 0; w = 1;
        }
        r[0] = 1 - 2 * (y * y + z * z); r[1] = 2 * (x * y + z * w);     r[2] = 2 * (x * z - y * w);
        r[4] = 2 * (x * y - z * w);     r[5] = 1 - 2 * (x * x + z * z); r[6] = 2 * (y * z + x * w);
        r[8] = 2 * (x * z + y * w);     r[9] = 2 * (y * z - x * w);     r[10] = 1 - 2 * (x * x + y * y);
    }
    if (node.scale.size() == 3) {
        s[0] = node.scale[0];
        s[5] = node.scale[1];
        s[10] = node.scale[2];
    }
    return mat_mul(t, mat_mul(r, s));
}

// Normal matrix: inverse transpose of the upper 3x3 (cofactor matrix; its
// scale does not matter since normals are renormalised).
void normal_matrix(const Mat &m, double out[9])
{
    double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], i = m[10];
    // cofactors, laid out so that n' = C * n (C = inverse transpose * det)
    out[0] = e * i - f * h; out[1] = -(d * i - f * g); out[2] = d * h - e * g;
    out[3] = -(b * i - c * h); out[4] = a * i - c * g; out[5] = -(a * h - b * g);
    out[6] = b * f - c * e; out[7] = -(a * f - c * d); out[8] = a * e - b * d;
}

size_t component_size(int type)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

double read_component(const unsigned char *p, int type, bool normalized)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: { signed char v = (signed char)p[0]; return normalized ? std::fmax(v / 127.0, -1.0) : v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
    case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return normalized ? std::fmax(v / 32767.0, -1.0) : v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    default: return 0;
    }
}

// Reads `count * ncomp` values from a buffer view range, bounds-checked.
void read_view(const tinygltf::Model &model, int view_index, size_t offset, size_t count, int ncomp,
               int ctype, bool normalized, std::vector<double> &out, size_t out_stride_elems,
               const std::vector<size_t> *targets, const char *what)
{
    if (view_index < 0 || view_index >= (int)model.bufferViews.size())
        throw Fail{std::string(what) + ": buffer view index out of range"};
    const tinygltf::BufferView &view = model.bufferViews[(size_t)view_index];
    if (view.buffer < 0 || view.buffer >= (int)model.buffers.size())
        throw Fail{std::string(what) + ": buffer index out of range"};
    const tinygltf::Buffer &buf = model.buffers[(size_t)view.buffer];
    size_t csize = component_size(ctype);
    if (csize == 0)
        throw Fail{std::string(what) + ": unsupported component type " + std::to_string(ctype)};
    size_t elem = csize * (size_t)ncomp;
    size_t stride = view.byteStride ? view.byteStride : elem;
    if (count > 0) {
        size_t last = view.byteOffset + offset + (count - 1) * stride + elem;
        if (last > view.byteOffset + view.byteLength || view.byteOffset + view.byteLength > buf.data.size())
            throw Fail{std::string(what) + ": accessor reads past the end of its buffer (truncated file?)"};
    }
    const unsigned char *base = buf.data.data() + view.byteOffset + offset;
    for (size_t i = 0; i < count; i++) {
        size_t dst = targets ? (*targets)[i] : i;
        if (dst >= out.size() / out_stride_elems)
            throw Fail{std::string(what) + ": sparse index " + std::to_string(dst) + " out of range"};
        for (int c = 0; c < ncomp; c++)
            out[dst * out_stride_elems + (size_t)c] = read_component(base + i * stride + (size_t)c * csize, ctype, normalized);
    }
}

int type_components(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

// An accessor as doubles, sparse substitution applied (glTF 2.0 §3.6.2.3).
std::vector<double> read_accessor(const tinygltf::Model &model, int index, int want_comp, const char *what)
{
    if (index < 0 || index >= (int)model.accessors.size())
        throw Fail{std::string(what) + ": accessor index out of range"};
    const tinygltf::Accessor &acc = model.accessors[(size_t)index];
    int ncomp = type_components(acc.type);
    if (ncomp != want_comp)
        throw Fail{std::string(what) + ": expected " + std::to_string(want_comp) + " components, got " + std::to_string(ncomp)};
    std::vector<double> out(acc.count * (size_t)ncomp, 0.0);
    if (acc.bufferView >= 0)
        read_view(model, acc.bufferView, acc.byteOffset, acc.count, ncomp, acc.componentType, acc.normalized, out,
                  (size_t)ncomp, nullptr, what);
    if (acc.sparse.isSparse) {
        size_t n = (size_t)acc.sparse.count;
        std::vector<double> idx(n);
        read_view(model, acc.sparse.indices.bufferView, (size_t)acc.sparse.indices.byteOffset, n, 1,
                  acc.sparse.indices.componentType, false, idx, 1, nullptr, what);
        std::vector<size_t> targets(n);
        for (size_t i = 0; i < n; i++)
            targets[i] = (size_t)idx[i];
        read_view(model, acc.sparse.values.bufferView, (size_t)acc.sparse.values.byteOffset, n, ncomp,
                  acc.componentType, acc.normalized, out, (size_t)ncomp, &targets, what);
    }
    return out;
}

struct Builder {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    int target_count = 0;
    std::vector<std::vector<float>> tpos, tnrm; // per target, grows with positions
    std::vector<float> weights;
    std::vector<std::string> target_names;
    gltf_material material{};
};

void read_material(const tinygltf::Model &model, int index, gltf_material &m)
{
    if (index < 0 || index >= (int)model.materials.size() || m.present)
        return;
    const tinygltf::Material &mat = model.materials[(size_t)index];
    m.present = true;
    m.ior = 1.5f;
    for (int c = 0; c < 3; c++) {
        m.base_color[c] = mat.pbrMetallicRoughness.baseColorFactor.size() == 4
                              ? (float)mat.pbrMetallicRoughness.baseColorFactor[(size_t)c] : 1.0f;
        m.attenuation_color[c] = 1.0f;
    }
    auto ext = mat.extensions.find("KHR_materials_transmission");
    if (ext != mat.extensions.end() && ext->second.Has("transmissionFactor"))
        m.transmission = (float)ext->second.Get("transmissionFactor").GetNumberAsDouble();
    ext = mat.extensions.find("KHR_materials_ior");
    if (ext != mat.extensions.end() && ext->second.Has("ior"))
        m.ior = (float)ext->second.Get("ior").GetNumberAsDouble();
    ext = mat.extensions.find("KHR_materials_volume");
    if (ext != mat.extensions.end()) {
        if (ext->second.Has("attenuationDistance"))
            m.attenuation_distance = (float)ext->second.Get("attenuationDistance").GetNumberAsDouble();
        if (ext->second.Has("attenuationColor")) {
            const tinygltf::Value &c = ext->second.Get("attenuationColor");
            for (int i = 0; i < 3 && i < (int)c.ArrayLen(); i++)
                m.attenuation_color[i] = (float)c.Get(i).GetNumberAsDouble();
        }
    }
    m.glass = m.transmission > 0.0f;
}

void add_primitive(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                   const Mat &world, Builder &b)
{
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES)
        return; // points and lines carry no surface
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end())
        throw Fail{"a primitive of mesh '" + mesh.name + "' has no POSITION"};
    std::vector<double> pos = read_accessor(model, pos_it->second, 3, "POSITION");
    size_t nv = pos.size() / 3;
    for (double v : pos)
        if (!std::isfinite(v))
            throw Fail{"mesh '" + mesh.name + "' has a non-finite (NaN or Inf) vertex position"};
    std::vector<double> nrm;
    auto n_it = prim.attributes.find("NORMAL");
    if (n_it != prim.attributes.end()) {
        nrm = read_accessor(model, n_it->second, 3, "NORMAL");
        if (nrm.size() != pos.size())
            throw Fail{"NORMAL and POSITION counts differ in mesh '" + mesh.name + "'"};
    }
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        std::vector<double> raw = read_accessor(model, prim.indices, 1, "indices");
        idx.reserve(raw.size());
        for (double v : raw) {
            if (v < 0 || v >= (double)nv)
                throw Fail{"mesh '" + mesh.name + "': index " + std::to_string((long long)v) +
                           " is out of range (the primitive has " + std::to_string(nv) + " vertices)"};
            idx.push_back((uint32_t)v);
        }
    } else {
        for (size_t i = 0; i < nv; i++)
            idx.push_back((uint32_t)i);
    }
    if (idx.size() % 3 != 0)
        throw Fail{"mesh '" + mesh.name + "': index count is not a multiple of 3"};

    double nm[9];
    normal_matrix(world, nm);
    size_t base = b.positions.size() / 3;
    if (base + nv > 0xffffffffu)
        throw Fail{"too many vertices"};
    for (size_t i = 0; i < nv; i++) {
        double x = pos[i * 3], y = pos[i * 3 + 1], z = pos[i * 3 + 2];
        for (int r = 0; r < 3; r++)
            b.positions.push_back((float)(world[r] * x + world[4 + r] * y + world[8 + r] * z + world[12 + r]));
    }
    // Normals: transformed by the normal matrix, or generated below.
    b.normals.resize(b.positions.size(), 0.0f);
    if (!nrm.empty()) {
        for (size_t i = 0; i < nv; i++) {
            double n[3];
            for (int r = 0; r < 3; r++)
                n[r] = nm[r * 3 + 0] * nrm[i * 3] + nm[r * 3 + 1] * nrm[i * 3 + 1] + nm[r * 3 + 2] * nrm[i * 3 + 2];
            double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int r = 0; r < 3; r++)
                b.normals[(base + i) * 3 + (size_t)r] = len > 1e-20 ? (float)(n[r] / len) : (r == 1 ? 1.0f : 0.0f);
        }
    } else {
        // Area-weighted vertex normals (the cross product's length is twice
        // the area, so summing unnormalised cross products weights by area).
        for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            const float *p0 = &b.positions[(base + idx[t]) * 3], *p1 = &b.positions[(base + idx[t + 1]) * 3],
                        *p2 = &b.positions[(base + idx[t + 2]) * 3];
            double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
            double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            for (int k = 0; k < 3; k++)
                for (int r = 0; r < 3; r++)
                    b.normals[(base + idx[t + (size_t)k]) * 3 + (size_t)r] += (float)c[r];
        }
        for (size_t i = 0; i < nv; i++) {
            float *n = &b.normals[(base + i) * 3];
            double len = std::sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            if (len > 1e-20) {
                n[0] = (float)(n[0] / len); n[1] = (float)(n[1] / len); n[2] = (float)(n[2] / len);
            } else {
                n[0] = 0; n[1] = 1; n[2] = 0; // a vertex of zero-area triangles only
            }
        }
    }
    for (uint32_t i : idx)
        b.indices.push_back((uint32_t)base + i);

    // Morph targets: per target index across primitives (weights are per mesh).
    int nt = (int)prim.targets.size();
    if (nt > b.target_count) {
        b.tpos.resize((size_t)nt);
        b.tnrm.resize((size_t)nt);
        for (int t = b.target_count; t < nt; t++) {
            b.tpos[(size_t)t].assign(base * 3, 0.0f);
            b.tnrm[(size_t)t].assign(base * 3, 0.0f);
        }
        b.target_count = nt;
        b.weights.resize((size_t)nt, 0.0f);
        b.target_names.resize((size_t)nt);
        for (int t = 0; t < nt; t++) {
            if (t < (int)mesh.weights.size())
                b.weights[(size_t)t] = (float)mesh.weights[(size_t)t];
        }
        tinygltf::Value names;
        if (mesh.extras.IsObject() && mesh.extras.Has("targetNames"))
            names = mesh.extras.Get("targetNames");
        for (int t = 0; t < nt && names.IsArray() && t < (int)names.ArrayLen(); t++)
            b.target_names[(size_t)t] = names.Get(t).IsString() ? names.Get(t).Get<std::string>() : "";
    }
    for (int t = 0; t < b.target_count; t++) {
        std::vector<float> &tp = b.tpos[(size_t)t], &tn = b.tnrm[(size_t)t];
        tp.resize(b.positions.size(), 0.0f);
        tn.resize(b.positions.size(), 0.0f);
        if (t >= nt)
            continue;
        const auto &target = prim.targets[(size_t)t];
        auto tp_it = target.find("POSITION");
        if (tp_it != target.end()) {
            std::vector<double> d = read_accessor(model, tp_it->second, 3, "morph target POSITION");
            if (d.size() != pos.size())
                throw Fail{"a morph target's POSITION count differs from the mesh's"};
            for (size_t i = 0; i < nv; i++) {
                if (!std::isfinite(d[i * 3]) || !std::isfinite(d[i * 3 + 1]) || !std::isfinite(d[i * 3 + 2]))
                    throw Fail{"a morph target has a non-finite position delta"};
                for (int r = 0; r < 3; r++)
                    tp[(base + i) * 3 + (size_t)r] = (float)(world[r] * d[i * 3] + world[4 + r] * d[i * 3 + 1] + world[8 + r] * d[i * 3 + 2]);
            }
        }
        auto tn_it = target.find("NORMAL");
        if (tn_it != target.end()) {
            std::vector<double> d = read_accessor(model, tn_it->second, 3, "morph target NORMAL");
            if (d.size() != pos.size())
                throw Fail{"a morph target's NORMAL count differs from the mesh's"};
            for (size_t i = 0; i < nv; i++)
                for (int r = 0; r < 3; r++)
                    tn[(base + i) * 3 + (size_t)r] = (float)(nm[r * 3] * d[i * 3] + nm[r * 3 + 1] * d[i * 3 + 1] + nm[r * 3 + 2] * d[i * 3 + 2]);
        }
    }
    read_material(model, prim.material, b.material);
}

void visit(const tinygltf::Model &model, int node_index, const Mat &parent, Builder &b, int depth)
{
    if (node_index < 0 || node_index >= (int)model.nodes.size())
        throw Fail{"node index " + std::to_string(node_index) + " is out of range"};
    if (depth > 64)
        throw Fail{"node hierarchy deeper than 64 levels (a cycle?)"};
    const tinygltf::Node &node = model.nodes[(size_t)node_index];
    Mat world = mat_mul(parent, node_matrix(node));
    if (node.mesh >= 0) {
        if (node.mesh >= (int)model.meshes.size())
            throw Fail{"mesh index " + std::to_string(node.mesh) + " is out of range"};
        const tinygltf::Mesh &mesh = model.meshes[(size_t)node.mesh];
        for (const auto &prim : mesh.primitives)
            add_primitive(model, mesh, prim, world, b);
    }
    for (int child : node.children)
        visit(model, child, world, b, depth + 1);
}

template <typename T> T *copy_out(const std::vector<T> &v)
{
    T *p = (T *)std::malloc(v.size() * sizeof(T) + 1);
    if (!p)
        throw Fail{"out of memory"};
    if (!v.empty())
        std::memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

} // namespace

extern "C" bool gltf_load(const char *path, struct gltf_mesh *out, struct error *err)
{
    std::memset(out, 0, sizeof *out);
    try {
        tinygltf::Model model;
        tinygltf::TinyGLTF loader;
        std::string gerr, gwarn;
        std::string p(path);
        bool binary = p.size() > 4 && (p.compare(p.size() - 4, 4, ".glb") == 0 || p.compare(p.size() - 4, 4, ".GLB") == 0);
        bool ok = binary ? loader.LoadBinaryFromFile(&model, &gerr, &gwarn, p)
                         : loader.LoadASCIIFromFile(&model, &gerr, &gwarn, p);
        if (!ok) {
            while (!gerr.empty() && (gerr.back() == '\n' || gerr.back() == ' '))
                gerr.pop_back();
            for (char &c : gerr)
                if (c == '\n')
                    c = ' ';
            throw Fail{"cannot load glTF: " + (gerr.empty() ? std::string("unknown error") : gerr)};
        }
        Builder b;
        std::vector<int> roots;
        int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (scene < (int)model.scenes.size())
            roots = model.scenes[(size_t)scene].nodes;
        else
            for (size_t i = 0; i < model.nodes.size(); i++)
                roots.push_back((int)i); // no scene: every node is a root (children visited twice is avoided below)
        if (model.scenes.empty()) {
            std::vector<bool> is_child(model.nodes.size(), false);
            for (const auto &n : model.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < (int)is_child.size())
                        is_child[(size_t)c] = true;
            roots.clear();
            for (size_t i = 0; i < model.nodes.size(); i++)
                if (!is_child[i])
                    roots.push_back((int)i);
        }
        for (int r : roots)
            visit(model, r, mat_identity(), b, 0);
        if (b.indices.empty())
            throw Fail{"no triangles in the default scene"};
        out->vertex_count = b.positions.size() / 3;
        out->index_count = b.indices.size();
        out->positions = copy_out(b.positions);
        out->normals = copy_out(b.normals);
        out->indices = copy_out(b.indices);
        out->material = b.material;
        out->target_count = b.target_count;
        if (b.target_count > 0) {
            std::vector<float> tp, tn;
            for (int t = 0; t < b.target_count; t++) {
                b.tpos[(size_t)t].resize(b.positions.size(), 0.0f);
                b.tnrm[(size_t)t].resize(b.positions.size(), 0.0f);
                tp.insert(tp.end(), b.tpos[(size_t)t].begin(), b.tpos[(size_t)t].end());
                tn.insert(tn.end(), b.tnrm[(size_t)t].begin(), b.tnrm[(size_t)t].end());
            }
            out->target_positions = copy_out(tp);
            out->target_normals = copy_out(tn);
            out->weights = copy_out(b.weights);
            out->target_names = (char **)std::calloc((size_t)b.target_count, sizeof(char *));
            for (int t = 0; t < b.target_count && out->target_names; t++)
                out->target_names[t] = strdup(b.target_names[(size_t)t].c_str());
        }
        return true;
    } catch (const Fail &f) {
        gltf_mesh_free(out);
        return error_set(err, "%s: %s", path, f.message.c_str());
    } catch (const std::exception &e) {
        gltf_mesh_free(out);
        return error_set(err, "%s: cannot load glTF: %s", path, e.what());
    }
}

extern "C" void gltf_mesh_free(struct gltf_mesh *mesh)
{
    std::free(mesh->positions);
    std::free(mesh->normals);
    std::free(mesh->indices);
    std::free(mesh->target_positions);
    std::free(mesh->target_normals);
    std::free(mesh->weights);
    if (mesh->target_names)
        for (int t = 0; t < mesh->target_count; t++)
            std::free(mesh->target_names[t]);
    std::free(mesh->target_names);
    std::memset(mesh, 0, sizeof *mesh);
}
