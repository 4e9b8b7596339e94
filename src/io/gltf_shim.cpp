// The project's only C++: a thin shim with a C interface over tinygltf
// (Debian's libtinygltf). It flattens the default scene into one triangle
// mesh, its primitives' index ranges each with its material, and validates
// what it reads: out-of-range indices, non-finite
// positions and truncated buffers are errors naming the file.
#include "io/gltf.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <unistd.h>

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

// Offsets and lengths come from the file: every sum and product is checked
// so that a byteOffset near 2^64 cannot wrap the bounds check.
size_t checked_add(size_t a, size_t b, const char *what)
{
    size_t r;
    if (__builtin_add_overflow(a, b, &r))
        throw Fail{std::string(what) + ": offset or length out of range"};
    return r;
}

size_t checked_mul(size_t a, size_t b, const char *what)
{
    size_t r;
    if (__builtin_mul_overflow(a, b, &r))
        throw Fail{std::string(what) + ": offset or length out of range"};
    return r;
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
    if (stride < elem)
        throw Fail{std::string(what) + ": byteStride " + std::to_string(stride) + " is smaller than an element"};
    size_t view_end = checked_add(view.byteOffset, view.byteLength, what);
    if (view_end > buf.data.size())
        throw Fail{std::string(what) + ": buffer view reads past the end of its buffer (truncated file?)"};
    if (count > 0) {
        size_t last = checked_add(checked_add(checked_add(view.byteOffset, offset, what),
                                              checked_mul(count - 1, stride, what), what),
                                  elem, what);
        if (last > view_end)
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
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

// The most elements an accessor may describe: what the file's binary data
// could hold one byte per element, or 1M for a small file (an accessor with
// no buffer view is all zeros, legal glTF, but its count must not ask for
// gigabytes a 1 KB file cannot describe).
size_t accessor_count_limit(const tinygltf::Model &model)
{
    size_t total = 0;
    for (const auto &b : model.buffers)
        total += b.data.size();
    return total > ((size_t)1 << 20) ? total : ((size_t)1 << 20);
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
    size_t limit = accessor_count_limit(model);
    if (acc.count > limit)
        throw Fail{std::string(what) + ": accessor count " + std::to_string(acc.count) +
                   " is larger than the file can describe"};
    std::vector<double> out(acc.count * (size_t)ncomp, 0.0);
    if (acc.bufferView >= 0)
        read_view(model, acc.bufferView, acc.byteOffset, acc.count, ncomp, acc.componentType, acc.normalized, out,
                  (size_t)ncomp, nullptr, what);
    if (acc.sparse.isSparse) {
        if (acc.sparse.count < 0 || (size_t)acc.sparse.count > acc.count)
            throw Fail{std::string(what) + ": sparse count " + std::to_string(acc.sparse.count) +
                       " is outside 0.." + std::to_string(acc.count)};
        if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
            throw Fail{std::string(what) + ": negative sparse byteOffset"};
        int itype = acc.sparse.indices.componentType;
        if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw Fail{std::string(what) + ": sparse indices must be unsigned integers, got component type " +
                       std::to_string(itype)};
        size_t n = (size_t)acc.sparse.count;
        std::vector<double> idx(n);
        read_view(model, acc.sparse.indices.bufferView, (size_t)acc.sparse.indices.byteOffset, n, 1,
                  itype, false, idx, 1, nullptr, what);
        std::vector<size_t> targets(n);
        for (size_t i = 0; i < n; i++) {
            if (!(idx[i] >= 0) || idx[i] >= (double)acc.count)
                throw Fail{std::string(what) + ": sparse index " + std::to_string((long long)idx[i]) + " out of range"};
            targets[i] = (size_t)idx[i];
        }
        read_view(model, acc.sparse.values.bufferView, (size_t)acc.sparse.values.byteOffset, n, ncomp,
                  acc.componentType, acc.normalized, out, (size_t)ncomp, &targets, what);
    }
    return out;
}

// Every texture a material holds (the one list its owners walk: the
// builder frees them, copying out hands them over, gltf_mesh_free frees them)
std::array<gltf_texture *, 12> material_textures(gltf_material &m)
{
    return {&m.base_color_texture, &m.normal_texture, &m.emissive_texture, &m.metallic_roughness_texture,
            &m.occlusion_texture, &m.transmission_texture, &m.specular_texture, &m.specular_color_texture,
            &m.thickness_texture, &m.clearcoat_texture, &m.clearcoat_roughness_texture,
            &m.clearcoat_normal_texture};
}

struct Builder {
    std::vector<float> positions, normals;
    std::vector<float> texcoords[2]; // zeros for primitives without the set
    bool has_texcoords[2] = {false, false};
    std::vector<float> colors; // COLOR_0 as RGBA, white for primitives without it
    bool has_colors = false;
    // JOINTS_0 and WEIGHTS_0 (a skin), read when the mesh is taken in its
    // own frame for a skinned node (gltf_file_mesh); zeros where a
    // primitive has none
    bool read_skin = false, has_skin = false;
    std::vector<float> joints, joint_weights;
    std::vector<float> tangents; // TANGENT (world xyz, w), or made per vertex; (0 0 0 1): none
    bool has_tangents = false;
    std::vector<uint32_t> indices;
    int target_count = 0;
    std::vector<std::vector<float>> tpos, tnrm; // per target, grows with positions
    std::vector<float> weights;
    std::vector<std::string> target_names;
    std::vector<gltf_material> materials; // owns their image bytes until copied out
    std::vector<int> slot_of;             // per glTF material: its index in `materials`, or -1 unread yet
    std::vector<gltf_range> ranges;
    ~Builder()
    {
        for (gltf_material &m : materials)
            for (gltf_texture *t : material_textures(m))
                std::free(t->bytes);
    }
};

// The image bytes of texture `index` and its sampler into t; the bytes
// stay undecoded here (keep_image_bytes put them in image.image).
void read_texture(const tinygltf::Model &model, int index, int texcoord, const tinygltf::ExtensionMap &extensions,
                  gltf_texture &t, const std::string &material)
{
    if (index < 0)
        return;
    if (index >= (int)model.textures.size())
        throw Fail{material + ": texture index " + std::to_string(index) + " is out of range"};
    const tinygltf::Texture &tex = model.textures[(size_t)index];
    if (tex.source < 0 || tex.source >= (int)model.images.size())
        throw Fail{material + ": texture " + std::to_string(index) + " has no image (source)"};
    const tinygltf::Image &img = model.images[(size_t)tex.source];
    const unsigned char *data = img.image.data();
    size_t size = img.image.size();
    if (img.bufferView >= 0) {
        // the image's own bytes inside its buffer, bounds checked (see keep_image_bytes)
        if (img.bufferView >= (int)model.bufferViews.size())
            throw Fail{material + ": image " + std::to_string(tex.source) + ": bufferView out of range"};
        const tinygltf::BufferView &view = model.bufferViews[(size_t)img.bufferView];
        if (view.buffer < 0 || view.buffer >= (int)model.buffers.size())
            throw Fail{material + ": image " + std::to_string(tex.source) + ": buffer out of range"};
        const std::vector<unsigned char> &buf = model.buffers[(size_t)view.buffer].data;
        if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset)
            throw Fail{material + ": image " + std::to_string(tex.source) + ": its bufferView runs past the buffer"};
        data = buf.data() + view.byteOffset;
        size = view.byteLength;
    }
    if (size == 0 && !img.uri.empty() && img.uri.compare(0, 5, "data:") != 0)
        // tinygltf went on without a file it could not read: name it
        throw Fail{material + ": image " + std::to_string(tex.source) + " '" + img.uri +
                   "': cannot read it (no such file beside the glTF file, or not readable); the file names it "
                   "relative to its own folder"};
    if (size == 0)
        throw Fail{material + ": image " + std::to_string(tex.source) + " has no data"};
    t.size = size;
    t.bytes = (uint8_t *)std::malloc(t.size);
    if (!t.bytes)
        throw Fail{"out of memory"};
    std::memcpy(t.bytes, data, t.size);
    std::snprintf(t.name, sizeof t.name, "image %d '%.60s'", tex.source, img.name.c_str());
    t.texcoord = texcoord;
    t.transform[0] = t.transform[3] = 1.0f;
    t.scale = 1.0f;
    t.mipmaps = true;
    if (tex.sampler >= 0 && tex.sampler < (int)model.samplers.size()) {
        const tinygltf::Sampler &s = model.samplers[(size_t)tex.sampler];
        auto wrap = [](int w) { return w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? 1
                                       : w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? 2 : 0; };
        t.wrap_s = wrap(s.wrapS);
        t.wrap_t = wrap(s.wrapT);
        t.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        t.mipmaps = s.minFilter == -1 || (s.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
                                          s.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR);
    }
    auto ext = extensions.find("KHR_texture_transform");
    if (ext != extensions.end()) {
        const tinygltf::Value &v = ext->second;
        double offset[2] = {0, 0}, scale[2] = {1, 1}, rotation = 0;
        for (int i = 0; i < 2; i++) {
            if (v.Has("offset") && v.Get("offset").ArrayLen() == 2)
                offset[i] = v.Get("offset").Get(i).GetNumberAsDouble();
            if (v.Has("scale") && v.Get("scale").ArrayLen() == 2)
                scale[i] = v.Get("scale").Get(i).GetNumberAsDouble();
        }
        if (v.Has("rotation"))
            rotation = v.Get("rotation").GetNumberAsDouble();
        if (v.Has("texCoord"))
            t.texcoord = v.Get("texCoord").GetNumberAsInt();
        // T * R * S with the README's example as the check: offset [0, 1],
        // rotation pi/2, scale 0.5 reads the lower left quadrant.
        double c = std::cos(rotation), s = std::sin(rotation);
        double m[6] = {c * scale[0], -s * scale[0], s * scale[1], c * scale[1], offset[0], offset[1]};
        for (int i = 0; i < 6; i++) {
            if (!std::isfinite(m[i]) || std::fabs(m[i]) > 1e6)
                throw Fail{material + ": KHR_texture_transform must be finite (and below 1e6)"};
            t.transform[i] = (float)m[i];
        }
    }
    if (t.texcoord != 0 && t.texcoord != 1)
        throw Fail{material + ": texCoord " + std::to_string(t.texcoord) + " (caustica reads TEXCOORD_0 and _1)"};
}

// The texture an extension names in its field `field` (a textureInfo:
// index, texCoord), if it names one, into t
void read_extension_texture(const tinygltf::Model &model, const tinygltf::Value &extension, const char *field,
                            gltf_texture &t, const std::string &material)
{
    if (!extension.Has(field))
        return;
    const tinygltf::Value &info = extension.Get(field);
    int index = info.Has("index") ? info.Get("index").GetNumberAsInt() : -1;
    int texcoord = info.Has("texCoord") ? info.Get("texCoord").GetNumberAsInt() : 0;
    read_texture(model, index, texcoord, tinygltf::ExtensionMap{}, t, material);
}

// Appends `what` to the material's list of things it asks for and nobody reads.
void note_unread(gltf_material &m, const std::string &what)
{
    size_t used = std::strlen(m.unread);
    if (used + 2 + what.size() + 1 > sizeof m.unread) { // never cut: counted instead
        m.unread_more++;
        return;
    }
    std::snprintf(m.unread + used, sizeof m.unread - used, "%s%s", used ? ", " : "", what.c_str());
}

// The extensions read here (KHR_texture_transform is read per texture).
bool extension_read(const std::string &name)
{
    return name == "KHR_materials_transmission" || name == "KHR_materials_ior" || name == "KHR_materials_volume" ||
           name == "KHR_materials_specular" || name == "KHR_materials_clearcoat" ||
           name == "KHR_materials_emissive_strength";
}

// KHR_materials_specular: the dielectric reflectance's factor and colour.
static void read_specular(const tinygltf::Model &model, const tinygltf::Material &mat, const tinygltf::Value &v,
                          gltf_material &m)
{
    if (v.Has("specularFactor"))
        m.specular = (float)v.Get("specularFactor").GetNumberAsDouble();
    if (v.Has("specularColorFactor")) {
        const tinygltf::Value &c = v.Get("specularColorFactor");
        for (int i = 0; i < 3 && i < (int)c.ArrayLen(); i++)
            m.specular_color[i] = (float)c.Get(i).GetNumberAsDouble();
    }
    std::string where = "material '" + mat.name + "'";
    read_extension_texture(model, v, "specularTexture", m.specular_texture, where);
    read_extension_texture(model, v, "specularColorTexture", m.specular_color_texture, where);
    if (!std::isfinite(m.specular) || m.specular < 0.0f || m.specular > 1.0f)
        throw Fail{where + ": KHR_materials_specular specularFactor must be in [0, 1]"};
    for (int c = 0; c < 3; c++)
        if (!std::isfinite(m.specular_color[c]) || m.specular_color[c] < 0.0f || m.specular_color[c] > 1e3f)
            throw Fail{where + ": KHR_materials_specular specularColorFactor must be in [0, 1000]"};
}

// KHR_materials_clearcoat: a second GGX lobe over the material (brdf.h).
static void read_clearcoat(const tinygltf::Model &model, const tinygltf::Material &mat, const tinygltf::Value &v,
                           gltf_material &m)
{
    std::string where = "material '" + mat.name + "'";
    if (v.Has("clearcoatFactor"))
        m.clearcoat = (float)v.Get("clearcoatFactor").GetNumberAsDouble();
    if (v.Has("clearcoatRoughnessFactor"))
        m.clearcoat_roughness = (float)v.Get("clearcoatRoughnessFactor").GetNumberAsDouble();
    read_extension_texture(model, v, "clearcoatTexture", m.clearcoat_texture, where);
    read_extension_texture(model, v, "clearcoatRoughnessTexture", m.clearcoat_roughness_texture, where);
    read_extension_texture(model, v, "clearcoatNormalTexture", m.clearcoat_normal_texture, where);
    if (v.Has("clearcoatNormalTexture") && v.Get("clearcoatNormalTexture").Has("scale"))
        m.clearcoat_normal_texture.scale = (float)v.Get("clearcoatNormalTexture").Get("scale").GetNumberAsDouble();
    if (!std::isfinite(m.clearcoat) || m.clearcoat < 0.0f || m.clearcoat > 1.0f ||
        !std::isfinite(m.clearcoat_roughness) || m.clearcoat_roughness < 0.0f || m.clearcoat_roughness > 1.0f)
        throw Fail{where + ": KHR_materials_clearcoat clearcoatFactor and clearcoatRoughnessFactor must be in [0, 1]"};
    if (!std::isfinite(m.clearcoat_normal_texture.scale) || std::fabs(m.clearcoat_normal_texture.scale) > 1e3)
        throw Fail{where + ": KHR_materials_clearcoat clearcoatNormalTexture.scale must be finite"};
}

// The rules c.material.glass applies (finite, IOR > 0, colours in
// [0, 1]): a file must not slip past them into NaN or negative absorption.
static void check_material(const tinygltf::Material &mat, const gltf_material &m)
{
    std::string name = "material '" + mat.name + "'";
    for (int c = 0; c < 3; c++) {
        if (!std::isfinite(m.base_color[c]) || m.base_color[c] < 0.0f)
            throw Fail{name + ": baseColorFactor must be finite and >= 0"};
        if (!std::isfinite(m.attenuation_color[c]) || m.attenuation_color[c] < 0.0f || m.attenuation_color[c] > 1.0f)
            throw Fail{name + ": KHR_materials_volume attenuationColor must be in [0, 1]"};
        if (!std::isfinite(m.emission[c]) || m.emission[c] < 0.0f)
            throw Fail{name + ": emissiveFactor x KHR_materials_emissive_strength must be finite and >= 0"};
    }
    if (!std::isfinite(m.ior) || !(m.ior > 0.0f))
        throw Fail{name + ": KHR_materials_ior ior must be a positive finite number, got " + std::to_string(m.ior)};
    if (!std::isfinite(m.transmission) || m.transmission < 0.0f || m.transmission > 1.0f)
        throw Fail{name + ": KHR_materials_transmission transmissionFactor must be in [0, 1]"};
    if (!std::isfinite(m.alpha) || m.alpha < 0.0f || m.alpha > 1.0f)
        throw Fail{name + ": baseColorFactor's alpha must be in [0, 1]"};
    if (!std::isfinite(m.metallic) || m.metallic < 0.0f || m.metallic > 1.0f || !std::isfinite(m.roughness) ||
        m.roughness < 0.0f || m.roughness > 1.0f)
        throw Fail{name + ": metallicFactor and roughnessFactor must be in [0, 1]"};
    if (!std::isfinite(m.alpha_cutoff) || m.alpha_cutoff < 0.0f)
        throw Fail{name + ": alphaCutoff must be a finite number >= 0"};
    // 0 stands for "infinite" (no absorption); anything else must be a
    // distance at which -ln(c)/d stays finite (c >= 1e-6 in mesh.c: d >= 1e-30
    // keeps 13.8/d below FLT_MAX).
    // A path length inside the glass in the mesh's units: finite and
    // >= 0 (1e308 was inf as a float, and a negative one turned absorption
    // into gain: NaN and Inf pixels). 1e6 units is past any scene's size.
    if (!std::isfinite(m.thickness) || m.thickness < 0.0f || m.thickness > 1e6f)
        throw Fail{name + ": KHR_materials_volume thicknessFactor must be a finite distance in [0, 1e6], got " +
                   std::to_string(m.thickness)};
    if (!std::isfinite(m.attenuation_distance) || m.attenuation_distance < 0.0f ||
        (m.attenuation_distance > 0.0f && m.attenuation_distance < 1e-30f))
        throw Fail{name + ": KHR_materials_volume attenuationDistance must be a positive finite distance"};
}

void read_material(const tinygltf::Model &model, int index, gltf_material &m)
{
    const tinygltf::Material &mat = model.materials[(size_t)index];
    if (mat.name.empty())
        std::snprintf(m.name, sizeof m.name, "material %d", index);
    else
        std::snprintf(m.name, sizeof m.name, "%s", mat.name.c_str());
    m.ior = 1.5f;
    const std::vector<double> &factor = mat.pbrMetallicRoughness.baseColorFactor;
    for (int c = 0; c < 3; c++) {
        m.base_color[c] = factor.size() == 4 ? (float)factor[(size_t)c] : 1.0f;
        m.attenuation_color[c] = 1.0f;
    }
    m.alpha = factor.size() == 4 ? (float)factor[3] : 1.0f;
    m.metallic = (float)mat.pbrMetallicRoughness.metallicFactor;
    m.roughness = (float)mat.pbrMetallicRoughness.roughnessFactor;
    m.alpha_mode = mat.alphaMode == "MASK" ? GLTF_ALPHA_MASK : mat.alphaMode == "BLEND" ? GLTF_ALPHA_BLEND
                                                                                         : GLTF_ALPHA_OPAQUE;
    m.alpha_cutoff = (float)mat.alphaCutoff;
    m.double_sided = mat.doubleSided;
    for (const auto &e : mat.extensions)
        if (!extension_read(e.first))
            note_unread(m, e.first);
    auto ext = mat.extensions.find("KHR_materials_transmission");
    if (ext != mat.extensions.end() && ext->second.Has("transmissionFactor"))
        m.transmission = (float)ext->second.Get("transmissionFactor").GetNumberAsDouble();
    if (ext != mat.extensions.end())
        read_extension_texture(model, ext->second, "transmissionTexture", m.transmission_texture,
                               "material '" + mat.name + "'");
    m.specular = 1.0f;
    for (int c = 0; c < 3; c++)
        m.specular_color[c] = 1.0f;
    ext = mat.extensions.find("KHR_materials_specular");
    if (ext != mat.extensions.end())
        read_specular(model, mat, ext->second, m);
    ext = mat.extensions.find("KHR_materials_clearcoat");
    if (ext != mat.extensions.end())
        read_clearcoat(model, mat, ext->second, m);
    ext = mat.extensions.find("KHR_materials_ior");
    if (ext != mat.extensions.end() && ext->second.Has("ior"))
        m.ior = (float)ext->second.Get("ior").GetNumberAsDouble();
    ext = mat.extensions.find("KHR_materials_volume");
    if (ext != mat.extensions.end()) {
        m.volume = true;
        if (ext->second.Has("thicknessFactor"))
            m.thickness = (float)ext->second.Get("thicknessFactor").GetNumberAsDouble();
        if (ext->second.Has("attenuationDistance"))
            m.attenuation_distance = (float)ext->second.Get("attenuationDistance").GetNumberAsDouble();
        read_extension_texture(model, ext->second, "thicknessTexture", m.thickness_texture,
                               "material '" + mat.name + "'");
        if (ext->second.Has("attenuationColor")) {
            const tinygltf::Value &c = ext->second.Get("attenuationColor");
            for (int i = 0; i < 3 && i < (int)c.ArrayLen(); i++)
                m.attenuation_color[i] = (float)c.Get(i).GetNumberAsDouble();
        }
    }
    float strength = 1.0f;
    ext = mat.extensions.find("KHR_materials_emissive_strength");
    if (ext != mat.extensions.end() && ext->second.Has("emissiveStrength"))
        strength = (float)ext->second.Get("emissiveStrength").GetNumberAsDouble();
    for (int c = 0; c < 3; c++)
        m.emission[c] = (mat.emissiveFactor.size() == 3 ? (float)mat.emissiveFactor[(size_t)c] : 0.0f) * strength;
    m.glass = m.transmission > 0.0f;
    {
        std::string where = "material '" + mat.name + "'";
        const tinygltf::TextureInfo &base = mat.pbrMetallicRoughness.baseColorTexture;
        read_texture(model, base.index, base.texCoord, base.extensions, m.base_color_texture, where);
        read_texture(model, mat.normalTexture.index, mat.normalTexture.texCoord, mat.normalTexture.extensions,
                     m.normal_texture, where);
        m.normal_texture.scale = (float)mat.normalTexture.scale;
        if (!std::isfinite(m.normal_texture.scale) || std::fabs(m.normal_texture.scale) > 1e3)
            throw Fail{where + ": normalTexture.scale must be finite"};
        read_texture(model, mat.emissiveTexture.index, mat.emissiveTexture.texCoord, mat.emissiveTexture.extensions,
                     m.emissive_texture, where);
        const tinygltf::TextureInfo &mr = mat.pbrMetallicRoughness.metallicRoughnessTexture;
        read_texture(model, mr.index, mr.texCoord, mr.extensions, m.metallic_roughness_texture, where);
        m.occlusion_strength = (float)mat.occlusionTexture.strength;
        if (!std::isfinite(m.occlusion_strength) || m.occlusion_strength < 0.0f || m.occlusion_strength > 1.0f)
            throw Fail{where + ": occlusionTexture.strength must be in [0, 1]"};
        read_texture(model, mat.occlusionTexture.index, mat.occlusionTexture.texCoord, mat.occlusionTexture.extensions,
                     m.occlusion_texture, where);
    }
    check_material(mat, m);
}

// The index in b.materials of glTF material `index` (read on first use), or
// -1 for none.
int material_slot(const tinygltf::Model &model, int index, Builder &b)
{
    if (index < 0 || index >= (int)model.materials.size())
        return -1; // a dangling index draws as no material, as before materials were per primitive
    if (b.slot_of.size() != model.materials.size())
        b.slot_of.assign(model.materials.size(), -1);
    if (b.slot_of[(size_t)index] < 0) {
        b.materials.push_back(gltf_material{});
        read_material(model, index, b.materials.back());
        b.slot_of[(size_t)index] = (int)b.materials.size() - 1;
    }
    return b.slot_of[(size_t)index];
}

// The primitive's triangle indices, checked (unsigned integers within its
// nv vertices, whole triangles); 0..nv-1 where it has none.
static std::vector<uint32_t> read_indices(const tinygltf::Model &model, const tinygltf::Mesh &mesh,
                                          const tinygltf::Primitive &prim, size_t nv)
{
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        // the spec allows unsigned byte, short and int indices only: a FLOAT
        // accessor's NaN or 7.5e28 would reach a cast to uint32_t
        if (prim.indices < (int)model.accessors.size()) {
            int type = model.accessors[(size_t)prim.indices].componentType;
            if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                throw Fail{"mesh '" + mesh.name + "': indices must be unsigned integers (glTF 2.0 3.7.2.1), got "
                           "component type " + std::to_string(type)};
        }
        std::vector<double> raw = read_accessor(model, prim.indices, 1, "indices");
        idx.reserve(raw.size());
        for (double v : raw) {
            if (!std::isfinite(v) || v < 0 || v >= (double)nv || v != std::floor(v))
                throw Fail{"mesh '" + mesh.name + "': index " + (std::isfinite(v) && std::fabs(v) < 1e18
                                                                     ? std::to_string((long long)v)
                                                                     : std::string("(not finite)")) +
                           " is out of range (the primitive has " + std::to_string(nv) + " vertices)"};
            idx.push_back((uint32_t)v);
        }
    } else {
        for (size_t i = 0; i < nv; i++)
            idx.push_back((uint32_t)i);
    }
    if (idx.size() % 3 != 0)
        throw Fail{"mesh '" + mesh.name + "': index count is not a multiple of 3"};

    return idx;
}

// Normals: the file's by the normal matrix nm, or area-weighted vertex
// normals of the primitive's triangles where it has none.
static void add_normals(Builder &b, const std::vector<double> &nrm, const double nm[9], const std::vector<uint32_t> &idx,
                        size_t base, size_t nv)
{
    b.normals.resize(b.positions.size(), 0.0f);
    if (!nrm.empty()) {
        for (size_t i = 0; i < nv; i++) {
            double n[3];
            for (int r = 0; r < 3; r++)
                n[r] = nm[r * 3 + 0] * nrm[i * 3] + nm[r * 3 + 1] * nrm[i * 3 + 1] + nm[r * 3 + 2] * nrm[i * 3 + 2];
            double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int r = 0; r < 3; r++)
                b.normals[(base + i) * 3 + (size_t)r] =
                    len > 1e-20 && std::isfinite(len) ? (float)(n[r] / len) : (r == 1 ? 1.0f : 0.0f);
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
}

// The skin (glTF 2.0 §3.7.3): four joints a vertex and their weights,
// normalised to sum 1 (a vertex of no weight stays put: joint 0 at
// weight 0 is no move, see deform.comp)
static void add_skin(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                     Builder &b, size_t base, size_t nv)
{
    b.joints.resize(base * 4, 0.0f);
    b.joint_weights.resize(base * 4, 0.0f);
    auto j_it = prim.attributes.find("JOINTS_0"), w_it = prim.attributes.find("WEIGHTS_0");
    if (j_it != prim.attributes.end() && w_it != prim.attributes.end()) {
        if (j_it->second < 0 || j_it->second >= (int)model.accessors.size())
            throw Fail{"JOINTS_0: accessor index out of range"};
        int jt = model.accessors[(size_t)j_it->second].componentType;
        if (jt != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && jt != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
            throw Fail{"JOINTS_0 of mesh '" + mesh.name + "' must be unsigned bytes or shorts"};
        std::vector<double> j = read_accessor(model, j_it->second, 4, "JOINTS_0");
        std::vector<double> w = read_accessor(model, w_it->second, 4, "WEIGHTS_0");
        if (j.size() != nv * 4 || w.size() != nv * 4)
            throw Fail{"JOINTS_0 or WEIGHTS_0 and POSITION counts differ in mesh '" + mesh.name + "'"};
        for (size_t i = 0; i < nv; i++) {
            double sum = 0;
            for (int k = 0; k < 4; k++) {
                double v = w[i * 4 + (size_t)k];
                sum += std::isfinite(v) && v > 0 ? v : 0;
            }
            for (int k = 0; k < 4; k++) {
                double v = w[i * 4 + (size_t)k];
                b.joints.push_back((float)j[i * 4 + (size_t)k]);
                b.joint_weights.push_back(sum > 0 && std::isfinite(v) && v > 0 ? (float)(v / sum) : 0.0f);
            }
        }
        b.has_skin = true;
    } else {
        b.joints.resize((base + nv) * 4, 0.0f);
        b.joint_weights.resize((base + nv) * 4, 0.0f);
    }
}

// TEXCOORD_0 and TEXCOORD_1 (0 0 where the primitive has none).
static void add_texcoords(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                          Builder &b, size_t base, size_t nv)
{
    for (int set = 0; set < 2; set++) {
        std::vector<float> &tc = b.texcoords[set];
        tc.resize(base * 2, 0.0f);
        auto it = prim.attributes.find(set == 0 ? "TEXCOORD_0" : "TEXCOORD_1");
        if (it == prim.attributes.end()) {
            tc.resize((base + nv) * 2, 0.0f);
            continue;
        }
        std::vector<double> uv = read_accessor(model, it->second, 2, set == 0 ? "TEXCOORD_0" : "TEXCOORD_1");
        if (uv.size() != nv * 2)
            throw Fail{"TEXCOORD and POSITION counts differ in mesh '" + mesh.name + "'"};
        for (double v : uv)
            tc.push_back(std::isfinite(v) && std::fabs(v) < 1e6 ? (float)v : 0.0f);
        b.has_texcoords[set] = true;
    }
}

// COLOR_0 (glTF 2.0 §3.7.2.1): VEC3 or VEC4, float or normalized
// unsigned byte/short, linear; it multiplies the base colour (and its
// alpha the material's). White for a primitive without it.
static void add_colors(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                       Builder &b, size_t base, size_t nv)
{
    b.colors.resize(base * 4, 1.0f);
    auto it = prim.attributes.find("COLOR_0");
    if (it == prim.attributes.end()) {
        b.colors.resize((base + nv) * 4, 1.0f);
    } else {
        if (it->second < 0 || it->second >= (int)model.accessors.size())
            throw Fail{"COLOR_0: accessor index out of range"};
        int ncomp = type_components(model.accessors[(size_t)it->second].type);
        if (ncomp != 3 && ncomp != 4)
            throw Fail{"COLOR_0 of mesh '" + mesh.name + "' must be VEC3 or VEC4"};
        std::vector<double> c = read_accessor(model, it->second, ncomp, "COLOR_0");
        if (c.size() != nv * (size_t)ncomp)
            throw Fail{"COLOR_0 and POSITION counts differ in mesh '" + mesh.name + "'"};
        for (size_t i = 0; i < nv; i++)
            for (int k = 0; k < 4; k++) {
                double v = k < ncomp ? c[i * (size_t)ncomp + (size_t)k] : 1.0;
                // a colour multiplies: in [0, 1] (a float one outside it is clamped)
                b.colors.push_back(std::isfinite(v) ? (float)std::fmin(std::fmax(v, 0.0), 1.0) : 1.0f);
            }
        b.has_colors = true;
    }
}

// Tangents for normal maps (issue 50): the file's TANGENT (its xyz by the
// node transform), else zero, which mesh_gltf.c has made by
// scene/mesh_tangents.c once the mesh is whole. Both renderers then take
// the tangent's direction from the interpolated attribute
// (docs/GLTF.md); (0 0 0 1): none.
static void add_tangents(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                         const Mat &world, Builder &b, size_t base, size_t nv, int slot)
{
    b.tangents.resize(base * 4, 0.0f);
    auto it = prim.attributes.find("TANGENT");
    const gltf_material *mat = slot >= 0 ? &b.materials[(size_t)slot] : nullptr;
    int set = mat && mat->normal_texture.bytes ? mat->normal_texture.texcoord
              : mat && mat->clearcoat_normal_texture.bytes ? mat->clearcoat_normal_texture.texcoord : -1;
    if (it != prim.attributes.end()) {
        if (it->second < 0 || it->second >= (int)model.accessors.size())
            throw Fail{"TANGENT: accessor index out of range"};
        if (type_components(model.accessors[(size_t)it->second].type) != 4)
            throw Fail{"TANGENT of mesh '" + mesh.name + "' must be VEC4"};
        std::vector<double> tg = read_accessor(model, it->second, 4, "TANGENT");
        if (tg.size() != nv * 4)
            throw Fail{"TANGENT and POSITION counts differ in mesh '" + mesh.name + "'"};
        double det = world[0] * (world[5] * world[10] - world[9] * world[6]) -
                     world[4] * (world[1] * world[10] - world[9] * world[2]) +
                     world[8] * (world[1] * world[6] - world[5] * world[2]);
        for (size_t i = 0; i < nv; i++) {
            double t[3];
            for (int r = 0; r < 3; r++)
                t[r] = world[r] * tg[i * 4] + world[4 + r] * tg[i * 4 + 1] + world[8 + r] * tg[i * 4 + 2];
            double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            bool ok = len > 1e-20 && std::isfinite(len) && std::isfinite(tg[i * 4 + 3]);
            for (int r = 0; r < 3; r++)
                b.tangents.push_back(ok ? (float)(t[r] / len) : 0.0f);
            b.tangents.push_back((tg[i * 4 + 3] < 0.0) != (det < 0.0) ? -1.0f : 1.0f);
        }
        b.has_tangents = true;
    } else if (set >= 0 && set < 2 && b.has_texcoords[set]) {
        // made from the normal map's texture coordinates after the mesh
        // is whole (scene/mesh_tangents.c: MikkTSpace's construction,
        // which splits vertices): zero here says "make me"
        b.tangents.resize((base + nv) * 4, 0.0f);
        b.has_tangents = true;
    } else {
        b.tangents.resize((base + nv) * 4, 0.0f);
    }
}

// Morph targets: per target index across primitives (weights are per mesh).
static void add_morph_targets(const tinygltf::Model &model, const tinygltf::Mesh &mesh, const tinygltf::Primitive &prim,
                              const Mat &world, const double nm[9], Builder &b, size_t base, size_t nv, size_t values)
{
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
            if (d.size() != values)
                throw Fail{"a morph target's POSITION count differs from the mesh's"};
            for (size_t i = 0; i < nv; i++) {
                if (!std::isfinite(d[i * 3]) || !std::isfinite(d[i * 3 + 1]) || !std::isfinite(d[i * 3 + 2]))
                    throw Fail{"a morph target has a non-finite position delta"};
                for (int r = 0; r < 3; r++) {
                    double v = world[r] * d[i * 3] + world[4 + r] * d[i * 3 + 1] + world[8 + r] * d[i * 3 + 2];
                    if (!std::isfinite(v) || std::fabs(v) > 1e30)
                        throw Fail{"a morph target's position delta is not finite after its node transform"};
                    tp[(base + i) * 3 + (size_t)r] = (float)v;
                }
            }
        }
        auto tn_it = target.find("NORMAL");
        if (tn_it != target.end()) {
            std::vector<double> d = read_accessor(model, tn_it->second, 3, "morph target NORMAL");
            if (d.size() != values)
                throw Fail{"a morph target's NORMAL count differs from the mesh's"};
            for (size_t i = 0; i < nv; i++)
                for (int r = 0; r < 3; r++) {
                    double v = nm[r * 3] * d[i * 3] + nm[r * 3 + 1] * d[i * 3 + 1] + nm[r * 3 + 2] * d[i * 3 + 2];
                    tn[(base + i) * 3 + (size_t)r] = std::isfinite(v) && std::fabs(v) < 1e30 ? (float)v : 0.0f;
                }
        }
    }
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
    std::vector<uint32_t> idx = read_indices(model, mesh, prim, nv);

    double nm[9];
    normal_matrix(world, nm);
    size_t base = b.positions.size() / 3;
    if (base + nv > 0xffffffffu)
        throw Fail{"too many vertices"};
    for (size_t i = 0; i < nv; i++) {
        double x = pos[i * 3], y = pos[i * 3 + 1], z = pos[i * 3 + 2];
        for (int r = 0; r < 3; r++) {
            // Checked after the node transform too: a scale of 1e300 turns
            // finite file values into Inf (or overflows the float).
            double v = world[r] * x + world[4 + r] * y + world[8 + r] * z + world[12 + r];
            if (!std::isfinite(v) || std::fabs(v) > 1e30)
                throw Fail{"mesh '" + mesh.name + "': a vertex position is not finite after its node transform"};
            b.positions.push_back((float)v);
        }
    }
    add_normals(b, nrm, nm, idx, base, nv);
    // This primitive's triangles and its material (a run of primitives with
    // one material stays one range).
    int slot = material_slot(model, prim.material, b);
    // Vertex attributes nothing draws yet (issue 50): said in the
    // material's list of what is ignored, once each, never dropped in silence
    if (slot >= 0 && !b.read_skin) {
        gltf_material &m = b.materials[(size_t)slot];
        static const char *const unread[][2] = {
            {"JOINTS_0", "JOINTS_0 and WEIGHTS_0 (a skin: drawn in its bind pose by c.mesh.load; c.gltf.load poses it)"}};
        for (const auto &u : unread)
            if (prim.attributes.count(u[0]) && !std::strstr(m.unread, u[0]))
                note_unread(m, u[1]);
    }
    if (b.read_skin)
        add_skin(model, mesh, prim, b, base, nv);
    if (!b.ranges.empty() && b.ranges.back().material == slot)
        b.ranges.back().index_count += idx.size();
    else
        b.ranges.push_back(gltf_range{b.indices.size(), idx.size(), slot});
    for (uint32_t i : idx)
        b.indices.push_back((uint32_t)base + i);
    add_texcoords(model, mesh, prim, b, base, nv);
    add_colors(model, mesh, prim, b, base, nv);
    add_tangents(model, mesh, prim, world, b, base, nv, slot);
    add_morph_targets(model, mesh, prim, world, nm, b, base, nv, pos.size());
}

// Instancing (a node listed by several parents) is legal glTF, so a node may
// be visited more than once; a DAG with fan-out can still ask for 2^24
// visits from a 1 KB file. These bound the expanded scene.
const size_t GLTF_MAX_NODE_VISITS = 100000;
const size_t GLTF_MAX_PRIMITIVES = 20000;
const size_t GLTF_MAX_VERTICES = (size_t)64 << 20;

struct VisitBudget {
    size_t nodes = 0, primitives = 0;
};

void visit(const tinygltf::Model &model, int node_index, const Mat &parent, Builder &b, int depth, VisitBudget &budget)
{
    if (node_index < 0 || node_index >= (int)model.nodes.size())
        throw Fail{"node index " + std::to_string(node_index) + " is out of range"};
    if (depth > 64)
        throw Fail{"node hierarchy deeper than 64 levels (a cycle?)"};
    if (++budget.nodes > GLTF_MAX_NODE_VISITS)
        throw Fail{"the node hierarchy expands to more than " + std::to_string(GLTF_MAX_NODE_VISITS) +
                   " node instances (nodes shared by many parents?)"};
    const tinygltf::Node &node = model.nodes[(size_t)node_index];
    Mat world = mat_mul(parent, node_matrix(node));
    if (node.mesh >= 0) {
        if (node.mesh >= (int)model.meshes.size())
            throw Fail{"mesh index " + std::to_string(node.mesh) + " is out of range"};
        const tinygltf::Mesh &mesh = model.meshes[(size_t)node.mesh];
        for (const auto &prim : mesh.primitives) {
            if (++budget.primitives > GLTF_MAX_PRIMITIVES)
                throw Fail{"the scene expands to more than " + std::to_string(GLTF_MAX_PRIMITIVES) +
                           " primitive instances"};
            add_primitive(model, mesh, prim, world, b);
            if (b.positions.size() / 3 > GLTF_MAX_VERTICES)
                throw Fail{"the scene expands to more than " + std::to_string(GLTF_MAX_VERTICES) + " vertices"};
        }
    }
    for (int child : node.children)
        visit(model, child, world, b, depth + 1, budget);
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

// Images are kept as their file's bytes, never decoded by tinygltf (a
// corrupt JPEG or an image view past the BIN chunk reached stb_image's bugs
// before): the caller decodes the ones a material uses with libpng/libjpeg
// (io/image_decode.c), which bound the size first.
//
// tinygltf hands an image in a bufferView over with the view's byteLength
// unchecked against its buffer (a view past the BIN chunk reads past the
// allocation): those are left here and read from the buffer with bounds
// checks by image_bytes(). URI images (data: or a file beside the glTF) come
// with their real length.
bool keep_image_bytes(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                      const unsigned char *bytes, int size, void *)
{
    if (image->bufferView < 0 && bytes && size > 0)
        image->image.assign(bytes, bytes + size);
    return true;
}

// External buffers are read only from the glTF's own folder and below, with
// no shell expansion of the URI (tinygltf's default ExpandFilePath runs
// wordexp): a file from somewhere else must not read /etc/shadow into vertices.
struct FsScope {
    std::string dir; // realpath of the glTF's folder
};

bool inside_scope(const std::string &path, const FsScope &scope)
{
    char *real = realpath(path.c_str(), nullptr);
    if (!real)
        return false;
    std::string r(real);
    std::free(real);
    return r.size() > scope.dir.size() && r.compare(0, scope.dir.size(), scope.dir) == 0 && r[scope.dir.size()] == '/';
}

// Says yes for any file that exists, so that scoped_read can say why one
// outside the folder is refused instead of "File not found".
bool scoped_file_exists(const std::string &path, void *)
{
    return access(path.c_str(), F_OK) == 0;
}

std::string scoped_expand(const std::string &path, void *) { return path; }

bool scoped_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    if (!inside_scope(path, *(const FsScope *)user)) {
        if (err)
            *err += "'" + path + "' is outside the glTF file's folder (external files must be beside it or below)\n";
        return false;
    }
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) {
        if (err)
            *err += "cannot open '" + path + "'\n";
        return false;
    }
    std::vector<unsigned char> data;
    unsigned char chunk[65536];
    size_t n;
    while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (data.size() + n > ((size_t)1 << 31)) {
            std::fclose(f);
            if (err)
                *err += "'" + path + "' is larger than 2 GiB\n";
            return false;
        }
        data.insert(data.end(), chunk, chunk + n);
    }
    std::fclose(f);
    *out = std::move(data);
    return true;
}

bool scoped_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err)
        *err += "caustica never writes glTF files\n";
    return false;
}

// tinygltf's JSON parser recurses once per nesting level: 10^5 levels in a
// 200 KB file overflow the stack. A glTF needs a handful of levels (extras a
// few more); refuse anything deeper before parsing.
const int GLTF_MAX_JSON_DEPTH = 128;

void check_json_depth(const unsigned char *json, size_t len)
{
    int depth = 0;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = json[i];
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
            continue;
        }
        if (c == '"')
            in_string = true;
        else if (c == '{' || c == '[') {
            if (++depth > GLTF_MAX_JSON_DEPTH)
                throw Fail{"JSON nested deeper than " + std::to_string(GLTF_MAX_JSON_DEPTH) + " levels"};
        } else if (c == '}' || c == ']')
            depth--;
    }
}

uint32_t read_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

std::vector<unsigned char> read_file(const std::string &path)
{
    std::vector<unsigned char> data;
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f)
        throw Fail{std::string("cannot open: ") + std::strerror(errno)};
    unsigned char chunk[65536];
    size_t n;
    while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (data.size() + n > ((size_t)1 << 31)) {
            std::fclose(f);
            throw Fail{"larger than 2 GiB"};
        }
        data.insert(data.end(), chunk, chunk + n);
    }
    bool bad = std::ferror(f);
    std::fclose(f);
    if (bad)
        throw Fail{"read error (is it a folder?)"};
    return data;
}

} // namespace

namespace {
// Parses the file at p into model: a GLB's or glTF's JSON (depth-checked
// first), its buffers read from its own folder only, images kept as bytes.
void parse_file(const std::string &p, tinygltf::Model &model)
{
    tinygltf::TinyGLTF loader;
    std::string gerr, gwarn;
    bool binary = p.size() > 4 && (p.compare(p.size() - 4, 4, ".glb") == 0 || p.compare(p.size() - 4, 4, ".GLB") == 0);
    std::vector<unsigned char> bytes = read_file(p);
    // The JSON part: the whole file, or the GLB's first chunk.
    if (binary) {
        if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
            throw Fail{"cannot load glTF: not a binary glTF file (no 'glTF' header)"};
        size_t json_len = read_u32(bytes.data() + 12);
        if (json_len > bytes.size() - 20)
            throw Fail{"cannot load glTF: the JSON chunk is longer than the file (truncated?)"};
        check_json_depth(bytes.data() + 20, json_len);
    } else {
        check_json_depth(bytes.data(), bytes.size());
    }
    char *dir_c = realpath(p.c_str(), nullptr);
    if (!dir_c)
        throw Fail{std::string("cannot open: ") + std::strerror(errno)};
    FsScope scope;
    scope.dir = dir_c;
    std::free(dir_c);
    scope.dir = scope.dir.substr(0, scope.dir.rfind('/'));
    if (scope.dir.empty())
        scope.dir = "/";
    tinygltf::FsCallbacks fs = {scoped_file_exists, scoped_expand, scoped_read, scoped_write, &scope};
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(keep_image_bytes, nullptr);
    bool ok = binary ? loader.LoadBinaryFromMemory(&model, &gerr, &gwarn, bytes.data(), (unsigned int)bytes.size(),
                                                   scope.dir)
                     : loader.LoadASCIIFromString(&model, &gerr, &gwarn, (const char *)bytes.data(),
                                                  (unsigned int)bytes.size(), scope.dir);
    if (!ok) {
        while (!gerr.empty() && (gerr.back() == '\n' || gerr.back() == ' '))
            gerr.pop_back();
        for (char &c : gerr)
            if (c == '\n')
                c = ' ';
        throw Fail{"cannot load glTF: " + (gerr.empty() ? std::string("unknown error") : gerr)};
    }
}

// What a Builder gathered, copied into out (which then owns the image bytes).
void builder_out(Builder &b, gltf_mesh *out)
{
    out->vertex_count = b.positions.size() / 3;
    out->index_count = b.indices.size();
    out->positions = copy_out(b.positions);
    out->normals = copy_out(b.normals);
    out->indices = copy_out(b.indices);
    for (int set = 0; set < 2; set++)
        if (b.has_texcoords[set]) {
            b.texcoords[set].resize(b.positions.size() / 3 * 2, 0.0f);
            out->texcoords[set] = copy_out(b.texcoords[set]);
        }
    if (b.has_tangents) {
        b.tangents.resize(b.positions.size() / 3 * 4, 0.0f);
        out->tangents = copy_out(b.tangents);
    }
    if (b.has_colors) {
        b.colors.resize(b.positions.size() / 3 * 4, 1.0f);
        out->colors = copy_out(b.colors);
    }
    if (b.has_skin) {
        b.joints.resize(b.positions.size() / 3 * 4, 0.0f);
        b.joint_weights.resize(b.positions.size() / 3 * 4, 0.0f);
        out->joints = copy_out(b.joints);
        out->joint_weights = copy_out(b.joint_weights);
    }
    out->material_count = (int)b.materials.size();
    out->materials = copy_out(b.materials);
    for (gltf_material &m : b.materials) // out owns the image bytes now
        for (gltf_texture *t : material_textures(m))
            t->bytes = nullptr;
    out->range_count = b.ranges.size();
    out->ranges = copy_out(b.ranges);
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
}
} // namespace

extern "C" bool gltf_load(const char *path, struct gltf_mesh *out, struct error *err)
{
    std::memset(out, 0, sizeof *out);
    try {
        tinygltf::Model model;
        parse_file(path, model);
        Builder b;
        std::vector<int> roots;
        int scene = model.defaultScene >= 0 && model.defaultScene < (int)model.scenes.size() ? model.defaultScene : 0;
        if (scene < (int)model.scenes.size())
            roots = model.scenes[(size_t)scene].nodes;
        if (model.scenes.empty()) {
            // no scene: every node no other names as a child is a root
            std::vector<bool> is_child(model.nodes.size(), false);
            for (const auto &n : model.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < (int)is_child.size())
                        is_child[(size_t)c] = true;
            for (size_t i = 0; i < model.nodes.size(); i++)
                if (!is_child[i])
                    roots.push_back((int)i);
        }
        VisitBudget budget;
        for (int r : roots)
            visit(model, r, mat_identity(), b, 0, budget);
        if (b.indices.empty())
            throw Fail{"no triangles in the default scene"};
        builder_out(b, out);
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
    std::free(mesh->texcoords[0]);
    std::free(mesh->texcoords[1]);
    std::free(mesh->colors);
    std::free(mesh->joints);
    std::free(mesh->joint_weights);
    std::free(mesh->tangents);
    for (int i = 0; mesh->materials && i < mesh->material_count; i++) {
        for (gltf_texture *t : material_textures(mesh->materials[i]))
            std::free(t->bytes);
    }
    std::free(mesh->materials);
    std::free(mesh->ranges);
    std::free(mesh->target_positions);
    std::free(mesh->target_normals);
    std::free(mesh->weights);
    if (mesh->target_names)
        for (int t = 0; t < mesh->target_count; t++)
            std::free(mesh->target_names[t]);
    std::free(mesh->target_names);
    std::memset(mesh, 0, sizeof *mesh);
}

// ---- a file as a scene ----------------------------------------------------

struct gltf_file {
    std::string path;
    tinygltf::Model model;
};

extern "C" bool gltf_file_open(const char *path, struct gltf_file **out, struct error *err)
{
    *out = nullptr;
    try {
        gltf_file *f = new gltf_file;
        f->path = path;
        try {
            parse_file(f->path, f->model);
        } catch (...) {
            delete f;
            throw;
        }
        *out = f;
        return true;
    } catch (const Fail &f) {
        return error_set(err, "%s: %s", path, f.message.c_str());
    } catch (const std::exception &e) {
        return error_set(err, "%s: cannot load glTF: %s", path, e.what());
    }
}

extern "C" void gltf_file_close(struct gltf_file *file) { delete file; }

extern "C" int gltf_file_mesh_count(const struct gltf_file *file) { return (int)file->model.meshes.size(); }

extern "C" bool gltf_file_mesh(const struct gltf_file *file, int index, struct gltf_mesh *out, struct error *err)
{
    std::memset(out, 0, sizeof *out);
    try {
        const tinygltf::Model &model = file->model;
        if (index < 0 || index >= (int)model.meshes.size())
            throw Fail{"mesh index " + std::to_string(index) + " is out of range"};
        const tinygltf::Mesh &mesh = model.meshes[(size_t)index];
        Builder b;
        b.read_skin = true;
        if (mesh.primitives.size() > GLTF_MAX_PRIMITIVES)
            throw Fail{"mesh " + std::to_string(index) + " has more than " + std::to_string(GLTF_MAX_PRIMITIVES) +
                       " primitives"};
        for (const auto &prim : mesh.primitives) {
            add_primitive(model, mesh, prim, mat_identity(), b);
            if (b.positions.size() / 3 > GLTF_MAX_VERTICES)
                throw Fail{"mesh " + std::to_string(index) + " has more than " + std::to_string(GLTF_MAX_VERTICES) +
                           " vertices"};
        }
        if (b.indices.empty())
            throw Fail{"mesh " + std::to_string(index) + " ('" + mesh.name + "') has no triangles"};
        builder_out(b, out);
        return true;
    } catch (const Fail &f) {
        gltf_mesh_free(out);
        return error_set(err, "%s: %s", file->path.c_str(), f.message.c_str());
    } catch (const std::exception &e) {
        gltf_mesh_free(out);
        return error_set(err, "%s: cannot load glTF: %s", file->path.c_str(), e.what());
    }
}

namespace {
void copy_name(char *dst, const std::string &name, const char *kind, size_t index)
{
    if (name.empty())
        std::snprintf(dst, GLTF_NAME, "%s %zu", kind, index);
    else
        std::snprintf(dst, GLTF_NAME, "%s", name.c_str());
}

bool finite_all(const std::vector<double> &v)
{
    for (double x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

// The rest pose of a node: its TRS, or its matrix (scene/gltf_pose.c
// decomposes it should an animation drive the node, which glTF forbids).
void node_rest(const tinygltf::Node &n, gltf_node &out, const std::string &what)
{
    out.translation[0] = out.translation[1] = out.translation[2] = 0;
    out.rotation[0] = out.rotation[1] = out.rotation[2] = 0;
    out.rotation[3] = 1;
    out.scale[0] = out.scale[1] = out.scale[2] = 1;
    if ((!n.translation.empty() && n.translation.size() != 3) || (!n.rotation.empty() && n.rotation.size() != 4) ||
        (!n.scale.empty() && n.scale.size() != 3) || (!n.matrix.empty() && n.matrix.size() != 16))
        throw Fail{what + ": translation, rotation, scale or matrix has the wrong number of values"};
    if (!finite_all(n.translation) || !finite_all(n.rotation) || !finite_all(n.scale) || !finite_all(n.matrix))
        throw Fail{what + ": its transform is not finite"};
    if (n.matrix.size() == 16) {
        out.has_matrix = true;
        for (int i = 0; i < 16; i++)
            out.matrix[i] = (float)n.matrix[(size_t)i];
        return;
    }
    for (size_t i = 0; i < n.translation.size(); i++)
        out.translation[i] = (float)n.translation[i];
    if (n.rotation.size() == 4) {
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (len > 1e-20) {
            out.rotation[0] = (float)(x / len);
            out.rotation[1] = (float)(y / len);
            out.rotation[2] = (float)(z / len);
            out.rotation[3] = (float)(w / len);
        }
    }
    for (size_t i = 0; i < n.scale.size(); i++)
        out.scale[i] = (float)n.scale[i];
}

// How many morph targets node n's mesh has (0 without a mesh).
int node_targets(const tinygltf::Model &model, const tinygltf::Node &n)
{
    if (n.mesh < 0 || n.mesh >= (int)model.meshes.size())
        return 0;
    const tinygltf::Mesh &mesh = model.meshes[(size_t)n.mesh];
    size_t t = mesh.weights.size();
    for (const auto &p : mesh.primitives)
        t = std::max(t, p.targets.size());
    return (int)t;
}

// Bounds the keys of all a file's animations: each is a time and up to
// 3 x 8 floats, so this caps the copy at about 1.6 GB... far below that,
// a script's memory limit applies to what it keeps (see l_gltf.c).
const size_t GLTF_MAX_KEYS = (size_t)16 << 20;

void read_channel(const tinygltf::Model &model, const tinygltf::Animation &anim, const tinygltf::AnimationChannel &ch,
                  const std::string &what, gltf_channel &out, size_t &keys_total)
{
    if (ch.target_node < 0 || ch.target_node >= (int)model.nodes.size())
        throw Fail{what + ": target node " + std::to_string(ch.target_node) + " is out of range"};
    if (ch.sampler < 0 || ch.sampler >= (int)anim.samplers.size())
        throw Fail{what + ": sampler " + std::to_string(ch.sampler) + " is out of range"};
    const tinygltf::AnimationSampler &sm = anim.samplers[(size_t)ch.sampler];
    out.node = ch.target_node;
    int comps;
    if (ch.target_path == "translation") {
        out.path = GLTF_PATH_TRANSLATION, comps = 3;
    } else if (ch.target_path == "rotation") {
        out.path = GLTF_PATH_ROTATION, comps = 4;
    } else if (ch.target_path == "scale") {
        out.path = GLTF_PATH_SCALE, comps = 3;
    } else if (ch.target_path == "weights") {
        out.path = GLTF_PATH_WEIGHTS;
        comps = node_targets(model, model.nodes[(size_t)ch.target_node]);
        if (comps == 0)
            throw Fail{what + ": animates the weights of node " + std::to_string(ch.target_node) +
                       ", whose mesh has no morph targets"};
        if (comps > GLTF_MAX_WEIGHTS)
            throw Fail{what + ": " + std::to_string(comps) + " morph weights, at most " +
                       std::to_string(GLTF_MAX_WEIGHTS) + " are supported"};
    } else {
        throw Fail{what + ": target path '" + ch.target_path + "' is not translation, rotation, scale or weights"};
    }
    if (sm.interpolation == "STEP")
        out.interpolation = GLTF_STEP;
    else if (sm.interpolation == "LINEAR" || sm.interpolation.empty())
        out.interpolation = GLTF_LINEAR;
    else if (sm.interpolation == "CUBICSPLINE")
        out.interpolation = GLTF_CUBICSPLINE;
    else
        throw Fail{what + ": interpolation '" + sm.interpolation + "' is not STEP, LINEAR or CUBICSPLINE"};
    out.components = comps;
    std::vector<double> times = read_accessor(model, sm.input, 1, (what + ": input").c_str());
    if (times.empty())
        throw Fail{what + ": no keyframes"};
    for (size_t i = 0; i < times.size(); i++) {
        if (!std::isfinite(times[i]))
            throw Fail{what + ": keyframe time " + std::to_string(i) + " is not finite"};
        if (i > 0 && times[i] < times[i - 1])
            throw Fail{what + ": keyframe times are not in order (key " + std::to_string(i) + " at " +
                       std::to_string(times[i]) + " s comes before key " + std::to_string(i - 1) + " at " +
                       std::to_string(times[i - 1]) + " s)"};
    }
    keys_total += times.size();
    if (keys_total > GLTF_MAX_KEYS)
        throw Fail{what + ": the animations hold more than " + std::to_string(GLTF_MAX_KEYS) + " keyframes"};
    size_t per_key = (size_t)comps * (out.interpolation == GLTF_CUBICSPLINE ? 3 : 1);
    // weights come as scalars, one per target per key
    if (sm.output < 0 || sm.output >= (int)model.accessors.size())
        throw Fail{what + ": output accessor index out of range"};
    int out_comps = out.path == GLTF_PATH_WEIGHTS ? 1 : comps;
    std::vector<double> values = read_accessor(model, sm.output, out_comps, (what + ": output").c_str());
    size_t want = times.size() * per_key;
    if (values.size() < want)
        throw Fail{what + ": output holds " + std::to_string(values.size() / (size_t)out_comps) + " values, " +
                   std::to_string(times.size()) + " keyframes need " + std::to_string(want / (size_t)out_comps)};
    if (!finite_all(values))
        throw Fail{what + ": an output value is not finite"};
    out.key_count = times.size();
    std::vector<float> tf(times.begin(), times.end()), vf(values.begin(), values.begin() + (long)want);
    out.times = copy_out(tf);
    try {
        out.values = copy_out(vf);
    } catch (...) {
        std::free(out.times);
        out.times = nullptr;
        throw;
    }
}
} // namespace

namespace {
// The scene chosen by name, index or the file's default: its index (-1:
// the file has none), name and the file's generator into out.
int scene_choose(const tinygltf::Model &model, const char *name, int index, gltf_scene *out)
{
    int scene = -1;
    if (name) {
        for (size_t i = 0; i < model.scenes.size() && scene < 0; i++)
            if (model.scenes[i].name == name)
                scene = (int)i;
        if (scene < 0) {
            std::string known;
            for (size_t i = 0; i < model.scenes.size(); i++)
                known += (i ? ", '" : "'") + model.scenes[i].name + "'";
            throw Fail{std::string("no scene named '") + name + "' (the file has " +
                       (known.empty() ? std::string("no named scene") : known) + ")"};
        }
    } else if (index >= 0) {
        if (index >= (int)model.scenes.size())
            throw Fail{"no scene " + std::to_string(index) + " (the file has " +
                       std::to_string(model.scenes.size()) + ", numbered from 0)"};
        scene = index;
    } else if (!model.scenes.empty()) {
        scene = model.defaultScene >= 0 && model.defaultScene < (int)model.scenes.size() ? model.defaultScene : 0;
    }
    out->index = scene;
    std::snprintf(out->generator, sizeof out->generator, "%s", model.asset.generator.c_str());
    if (scene >= 0)
        copy_name(out->name, model.scenes[(size_t)scene].name, "scene", (size_t)scene);
    else
        std::snprintf(out->name, GLTF_NAME, "(no scene)");
    return scene;
}

// Every node: its name, mesh, camera, light, skin, rest pose and weights;
// the tree's parents, checked for a node of two parents, cycles and depth.
void scene_nodes(const tinygltf::Model &model, gltf_scene *out)
{
    size_t nn = model.nodes.size();
    out->nodes = (gltf_node *)std::calloc(nn ? nn : 1, sizeof *out->nodes);
    if (!out->nodes)
        throw Fail{"out of memory"};
    out->node_count = (int)nn;
    for (size_t i = 0; i < nn; i++) {
        const tinygltf::Node &n = model.nodes[i];
        gltf_node &g = out->nodes[i];
        copy_name(g.name, n.name, "node", i);
        g.parent = -1;
        g.mesh = n.mesh;
        g.camera = n.camera;
        g.light = -1;
        std::string what = "node " + std::to_string(i) + " ('" + g.name + "')";
        if (n.mesh >= (int)model.meshes.size() || n.mesh < -1)
            throw Fail{what + ": mesh index " + std::to_string(n.mesh) + " is out of range"};
        if (n.camera >= (int)model.cameras.size() || n.camera < -1)
            throw Fail{what + ": camera index " + std::to_string(n.camera) + " is out of range"};
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end() && ext->second.Has("light")) {
            const tinygltf::Value &l = ext->second.Get("light");
            int li = l.IsInt() ? l.Get<int>() : l.IsNumber() ? (int)l.Get<double>() : -1;
            if (li < 0 || li >= (int)model.lights.size())
                throw Fail{what + ": KHR_lights_punctual light " + std::to_string(li) + " is out of range"};
            g.light = li;
        }
        g.skin = n.skin;
        if (n.skin >= (int)model.skins.size() || n.skin < -1)
            throw Fail{what + ": skin index " + std::to_string(n.skin) + " is out of range"};
        node_rest(n, g, what);
        g.weight_count = node_targets(model, n);
        if (g.weight_count > GLTF_MAX_WEIGHTS)
            throw Fail{what + ": " + std::to_string(g.weight_count) + " morph targets, at most " +
                       std::to_string(GLTF_MAX_WEIGHTS) + " are supported"};
        const std::vector<double> *w = !n.weights.empty() ? &n.weights
                                       : n.mesh >= 0 ? &model.meshes[(size_t)n.mesh].weights : nullptr;
        for (int k = 0; w && k < g.weight_count && k < (int)w->size(); k++)
            g.weights[k] = std::isfinite((*w)[(size_t)k]) ? (float)(*w)[(size_t)k] : 0.0f;
    }
    // parents: glTF's node hierarchy is a set of disjoint trees
    for (size_t i = 0; i < nn; i++)
        for (int c : model.nodes[i].children) {
            if (c < 0 || c >= (int)nn)
                throw Fail{"node " + std::to_string(i) + ": child " + std::to_string(c) + " is out of range"};
            if (c == (int)i)
                throw Fail{"node " + std::to_string(i) + " is its own child (a cycle)"};
            if (out->nodes[c].parent >= 0)
                throw Fail{"node " + std::to_string(c) + " is a child of both node " +
                           std::to_string(out->nodes[c].parent) + " and node " + std::to_string(i) +
                           " (glTF allows one parent)"};
            out->nodes[c].parent = (int)i;
        }
    // depth and cycles: walk up from each node
    const int max_depth = 256;
    for (size_t i = 0; i < nn; i++) {
        int depth = 0;
        for (int p = out->nodes[i].parent; p >= 0; p = out->nodes[p].parent) {
            if (++depth <= max_depth)
                continue;
            // too deep, or going round: a cycle comes back to a node within nn steps
            int q = out->nodes[i].parent;
            for (size_t step = 0; step <= nn && q >= 0; step++, q = out->nodes[q].parent)
                if (q == (int)i)
                    throw Fail{"node " + std::to_string(i) + " is its own ancestor (a cycle in the node tree)"};
            throw Fail{"node " + std::to_string(i) + " lies more than " + std::to_string(max_depth) +
                       " levels deep in the node tree (at most " + std::to_string(max_depth) + ")"};
        }
    }
}

// Which nodes lie under the chosen scene's roots (every tree without one).
void scene_mark(const tinygltf::Model &model, int scene, gltf_scene *out)
{
    size_t nn = model.nodes.size();
    // the chosen scene's nodes
    if (scene >= 0) {
        for (int r : model.scenes[(size_t)scene].nodes) {
            if (r < 0 || r >= (int)nn)
                throw Fail{"scene " + std::to_string(scene) + ": node " + std::to_string(r) + " is out of range"};
            if (out->nodes[r].parent >= 0)
                throw Fail{"scene " + std::to_string(scene) + ": root node " + std::to_string(r) +
                           " is also the child of node " + std::to_string(out->nodes[r].parent)};
        }
        for (size_t i = 0; i < nn; i++) {
            int root = (int)i;
            while (out->nodes[root].parent >= 0)
                root = out->nodes[root].parent;
            for (int r : model.scenes[(size_t)scene].nodes)
                if (r == root)
                    out->nodes[i].in_scene = true;
        }
    } else {
        for (size_t i = 0; i < nn; i++)
            out->nodes[i].in_scene = true; // no scene: every tree
    }
}

void scene_cameras(const tinygltf::Model &model, gltf_scene *out)
{
    out->cameras = (gltf_camera *)std::calloc(model.cameras.size() + 1, sizeof *out->cameras);
    if (!out->cameras)
        throw Fail{"out of memory"};
    out->camera_count = (int)model.cameras.size();
    for (size_t i = 0; i < model.cameras.size(); i++) {
        const tinygltf::Camera &c = model.cameras[i];
        gltf_camera &g = out->cameras[i];
        copy_name(g.name, c.name, "camera", i);
        std::string what = "camera " + std::to_string(i) + " ('" + g.name + "')";
        if (c.type == "orthographic") {
            g.orthographic = true;
            g.xmag = (float)c.orthographic.xmag;
            g.ymag = (float)c.orthographic.ymag;
            g.znear = (float)c.orthographic.znear;
            g.zfar = (float)c.orthographic.zfar;
            if (!(std::isfinite(g.xmag) && std::isfinite(g.ymag) && g.xmag != 0 && g.ymag != 0))
                throw Fail{what + ": xmag and ymag must be finite and not zero"};
            if (!(g.znear >= 0 && g.zfar > g.znear && std::isfinite(g.zfar)))
                throw Fail{what + ": znear must be 0 or more and zfar greater"};
        } else if (c.type == "perspective") {
            g.yfov = (float)c.perspective.yfov;
            g.aspect = (float)c.perspective.aspectRatio;
            g.znear = (float)c.perspective.znear;
            g.zfar = (float)c.perspective.zfar;
            if (!(g.yfov > 0 && g.yfov < 3.14159f))
                throw Fail{what + ": yfov " + std::to_string(g.yfov) + " is not in (0, pi) radians"};
            if (!(g.znear > 0 && std::isfinite(g.znear)) || !(g.zfar == 0 || g.zfar > g.znear) ||
                !std::isfinite(g.zfar))
                throw Fail{what + ": znear must be positive and zfar greater (or absent)"};
            if (!(g.aspect >= 0 && std::isfinite(g.aspect)))
                g.aspect = 0;
        } else {
            throw Fail{what + ": type '" + c.type + "' is not perspective or orthographic"};
        }
    }
}

void scene_lights(const tinygltf::Model &model, gltf_scene *out)
{
    out->lights = (gltf_light *)std::calloc(model.lights.size() + 1, sizeof *out->lights);
    if (!out->lights)
        throw Fail{"out of memory"};
    out->light_count = (int)model.lights.size();
    for (size_t i = 0; i < model.lights.size(); i++) {
        const tinygltf::Light &l = model.lights[i];
        gltf_light &g = out->lights[i];
        copy_name(g.name, l.name, "light", i);
        std::string what = "light " + std::to_string(i) + " ('" + g.name + "')";
        if (l.type == "directional")
            g.kind = GLTF_LIGHT_DIRECTIONAL;
        else if (l.type == "point")
            g.kind = GLTF_LIGHT_POINT;
        else if (l.type == "spot")
            g.kind = GLTF_LIGHT_SPOT;
        else
            throw Fail{what + ": type '" + l.type + "' is not directional, point or spot"};
        g.color[0] = g.color[1] = g.color[2] = 1;
        if (l.color.size() == 3)
            for (int k = 0; k < 3; k++)
                g.color[k] = (float)l.color[(size_t)k];
        g.intensity = (float)l.intensity;
        g.range = (float)l.range;
        g.inner_cone = (float)l.spot.innerConeAngle;
        g.outer_cone = (float)l.spot.outerConeAngle;
        if (!(g.intensity >= 0 && std::isfinite(g.intensity)) ||
            !(g.color[0] >= 0 && g.color[1] >= 0 && g.color[2] >= 0 && std::isfinite(g.color[0] + g.color[1] + g.color[2])))
            throw Fail{what + ": intensity and color must be finite and not negative"};
        if (g.kind == GLTF_LIGHT_SPOT &&
            !(g.inner_cone >= 0 && g.outer_cone > g.inner_cone - 1e-6f && g.outer_cone <= 1.5708f))
            throw Fail{what + ": spot cones must satisfy 0 <= inner < outer <= pi/2"};
        if (!(g.range >= 0 && std::isfinite(g.range)))
            g.range = 0;
    }
}

void scene_skins(const tinygltf::Model &model, gltf_scene *out)
{
    size_t nn = model.nodes.size();
    // skins: joints that are nodes, an inverse bind matrix each
    out->skins = (gltf_skin *)std::calloc(model.skins.size() + 1, sizeof *out->skins);
    if (!out->skins)
        throw Fail{"out of memory"};
    for (size_t i = 0; i < model.skins.size(); i++) {
        const tinygltf::Skin &sk = model.skins[i];
        gltf_skin &g = out->skins[i];
        out->skin_count = (int)i + 1; // freed from here on
        copy_name(g.name, sk.name, "skin", i);
        std::string what = "skin " + std::to_string(i) + " ('" + g.name + "')";
        if (sk.joints.empty())
            throw Fail{what + ": no joints"};
        if (sk.joints.size() > GLTF_MAX_JOINTS)
            throw Fail{what + ": " + std::to_string(sk.joints.size()) + " joints, at most " +
                       std::to_string(GLTF_MAX_JOINTS) + " are supported"};
        g.joints = (int *)std::calloc(sk.joints.size(), sizeof *g.joints);
        g.inverse_bind = (float *)std::calloc(sk.joints.size() * 16, sizeof *g.inverse_bind);
        if (!g.joints || !g.inverse_bind)
            throw Fail{"out of memory"};
        g.joint_count = (int)sk.joints.size();
        for (size_t k = 0; k < sk.joints.size(); k++) {
            if (sk.joints[k] < 0 || sk.joints[k] >= (int)nn)
                throw Fail{what + ": joint " + std::to_string(k) + " is node " + std::to_string(sk.joints[k]) +
                           ", out of range (the file has " + std::to_string(nn) + " nodes)"};
            g.joints[k] = sk.joints[k];
            for (int c = 0; c < 16; c++)
                g.inverse_bind[k * 16 + (size_t)c] = c % 5 == 0 ? 1.0f : 0.0f;
        }
        if (sk.inverseBindMatrices >= 0) {
            std::vector<double> ibm = read_accessor(model, sk.inverseBindMatrices, 16,
                                                    (what + ": inverseBindMatrices").c_str());
            if (ibm.size() < sk.joints.size() * 16)
                throw Fail{what + ": inverseBindMatrices holds " + std::to_string(ibm.size() / 16) +
                           " matrices for " + std::to_string(sk.joints.size()) + " joints"};
            if (!finite_all(ibm))
                throw Fail{what + ": an inverse bind matrix is not finite"};
            for (size_t k = 0; k < sk.joints.size() * 16; k++)
                g.inverse_bind[k] = (float)ibm[k];
        }
    }
}

void scene_animations(const tinygltf::Model &model, gltf_scene *out)
{
    size_t na = model.animations.size();
    out->animations = (gltf_animation *)std::calloc(na + 1, sizeof *out->animations);
    if (!out->animations)
        throw Fail{"out of memory"};
    size_t keys_total = 0;
    for (size_t a = 0; a < na; a++) {
        const tinygltf::Animation &anim = model.animations[a];
        gltf_animation &g = out->animations[a];
        out->animation_count = (int)a + 1; // freed from here on
        copy_name(g.name, anim.name, "animation", a);
        g.channels = (gltf_channel *)std::calloc(anim.channels.size() + 1, sizeof *g.channels);
        if (!g.channels)
            throw Fail{"out of memory"};
        g.start = INFINITY;
        g.end = -INFINITY;
        for (size_t k = 0; k < anim.channels.size(); k++) {
            std::string what = "animation " + std::to_string(a) + " ('" + g.name + "') channel " + std::to_string(k);
            read_channel(model, anim, anim.channels[k], what, g.channels[k], keys_total);
            g.channel_count = (int)k + 1;
            g.start = std::min(g.start, g.channels[k].times[0]);
            g.end = std::max(g.end, g.channels[k].times[g.channels[k].key_count - 1]);
        }
        if (g.channel_count == 0)
            g.start = g.end = 0;
    }
}
} // namespace

extern "C" bool gltf_file_scene(const struct gltf_file *file, const char *name, int index, struct gltf_scene *out,
                                struct error *err)
{
    std::memset(out, 0, sizeof *out);
    try {
        const tinygltf::Model &model = file->model;
        int scene = scene_choose(model, name, index, out);
        scene_nodes(model, out);
        scene_mark(model, scene, out);
        scene_cameras(model, out);
        scene_lights(model, out);
        scene_skins(model, out);
        scene_animations(model, out);
        return true;
    } catch (const Fail &f) {
        gltf_scene_free(out);
        return error_set(err, "%s: %s", file->path.c_str(), f.message.c_str());
    } catch (const std::exception &e) {
        gltf_scene_free(out);
        return error_set(err, "%s: cannot load glTF: %s", file->path.c_str(), e.what());
    }
}

extern "C" void gltf_scene_free(struct gltf_scene *scene)
{
    std::free(scene->nodes);
    std::free(scene->cameras);
    std::free(scene->lights);
    for (int a = 0; scene->animations && a < scene->animation_count; a++) {
        for (int k = 0; k < scene->animations[a].channel_count; k++) {
            std::free(scene->animations[a].channels[k].times);
            std::free(scene->animations[a].channels[k].values);
        }
        std::free(scene->animations[a].channels);
    }
    std::free(scene->animations);
    for (int k = 0; scene->skins && k < scene->skin_count; k++) {
        std::free(scene->skins[k].joints);
        std::free(scene->skins[k].inverse_bind);
    }
    std::free(scene->skins);
    std::memset(scene, 0, sizeof *scene);
}
