#include "gl/gl_texture.h"

#include <stdlib.h>
#include <string.h>

static const struct {
    const char *name;
    GLenum format;
} format_names[] = {
    {"rgba8", GL_RGBA8},     {"rgba16f", GL_RGBA16F}, {"rgba32f", GL_RGBA32F}, {"rg16f", GL_RG16F},
    {"rg32f", GL_RG32F},     {"r16f", GL_R16F},       {"r32f", GL_R32F},       {"r32ui", GL_R32UI},
    {"r8", GL_R8},           {"depth24", GL_DEPTH_COMPONENT24}, {"depth32f", GL_DEPTH_COMPONENT32F},
};

bool gl_format_parse(const char *name, GLenum *format)
{
    for (size_t i = 0; i < sizeof format_names / sizeof format_names[0]; i++)
        if (strcmp(format_names[i].name, name) == 0) {
            *format = format_names[i].format;
            return true;
        }
    return false;
}

const char *gl_format_name(GLenum format)
{
    for (size_t i = 0; i < sizeof format_names / sizeof format_names[0]; i++)
        if (format_names[i].format == format)
            return format_names[i].name;
    return "?";
}

bool gl_format_is_depth(GLenum format)
{
    return format == GL_DEPTH_COMPONENT24 || format == GL_DEPTH_COMPONENT32F;
}

bool gl_texture_create(struct gl_texture *tex, GLenum target, GLenum format, int width, int height,
                       int layers, struct error *err)
{
    return gl_texture_create_levels(tex, target, format, width, height, layers, 1, err);
}

bool gl_texture_create_levels(struct gl_texture *tex, GLenum target, GLenum format, int width, int height,
                              int layers, int levels, struct error *err)
{
    memset(tex, 0, sizeof *tex);
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return error_set(err, "texture size %dx%d is out of range (1..16384)", width, height);
    int full = 1;
    for (int side = width > height ? width : height; side > 1; side /= 2)
        full++;
    if (levels <= 0 || levels > full)
        levels = full;
    gl.CreateTextures(target, 1, &tex->id);
    if (target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_3D)
        gl.TextureStorage3D(tex->id, levels, format, width, height, layers > 0 ? layers : 1);
    else
        gl.TextureStorage2D(tex->id, levels, format, width, height);
    bool is_int = format == GL_R32UI || format == GL_RG32UI || format == GL_RGBA32UI || format == GL_R32I;
    GLint filter = is_int ? GL_NEAREST : GL_LINEAR;
    gl.TextureParameteri(tex->id, GL_TEXTURE_MIN_FILTER, levels > 1 && !is_int ? GL_LINEAR_MIPMAP_LINEAR : filter);
    gl.TextureParameteri(tex->id, GL_TEXTURE_MAG_FILTER, filter);
    gl.TextureParameteri(tex->id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(tex->id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(tex->id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    tex->target = target;
    tex->format = format;
    tex->width = width;
    tex->height = height;
    tex->layers = target == GL_TEXTURE_CUBE_MAP ? 6 : (layers > 0 ? layers : 1);
    if (!gl_check("texture creation", err)) {
        gl_texture_destroy(tex);
        return error_prefix(err, "%s %dx%d", gl_format_name(format), width, height);
    }
    return true;
}

void gl_texture_destroy(struct gl_texture *tex)
{
    if (tex->id && gl_api_ready())
        gl.DeleteTextures(1, &tex->id);
    memset(tex, 0, sizeof *tex);
}

bool gl_texture_read_depth32f(const struct gl_texture *tex, float *out, struct error *err)
{
    struct gl_framebuffer fb;
    if (!gl_framebuffer_create(&fb, err))
        return false;
    bool ok = gl_framebuffer_attach(&fb, NULL, NULL, 0, tex, -1, err);
    if (ok) {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fb.id);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadPixels(0, 0, tex->width, tex->height, GL_DEPTH_COMPONENT, GL_FLOAT, out);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        ok = gl_check("reading a depth texture back", err);
    }
    gl_framebuffer_destroy(&fb);
    return ok;
}

bool gl_texture_read_rgba32f(const struct gl_texture *tex, int layer, float *out, struct error *err)
{
    /* Read through a framebuffer so that one layer of a cube map or array
     * can be read, and so the format conversion is the driver's. */
    struct gl_framebuffer fb;
    if (!gl_framebuffer_create(&fb, err))
        return false;
    const struct gl_texture *colors[1] = {tex};
    int layers[1] = {tex->target == GL_TEXTURE_2D ? -1 : layer};
    bool ok = gl_framebuffer_attach(&fb, colors, layers, 1, NULL, -1, err);
    if (ok) {
        gl.NamedFramebufferReadBuffer(fb.id, GL_COLOR_ATTACHMENT0);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fb.id);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadPixels(0, 0, tex->width, tex->height, GL_RGBA, GL_FLOAT, out);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        ok = gl_check("reading a texture back", err);
    }
    gl_framebuffer_destroy(&fb);
    return ok;
}

bool gl_framebuffer_create(struct gl_framebuffer *fb, struct error *err)
{
    fb->id = 0;
    gl.CreateFramebuffers(1, &fb->id);
    return gl_check("framebuffer creation", err);
}

void gl_framebuffer_destroy(struct gl_framebuffer *fb)
{
    if (fb->id && gl_api_ready())
        gl.DeleteFramebuffers(1, &fb->id);
    fb->id = 0;
}

bool gl_framebuffer_attach(struct gl_framebuffer *fb, const struct gl_texture *const *colors,
                           const int *color_layers, int ncolors, const struct gl_texture *depth,
                           int depth_layer, struct error *err)
{
    GLenum buffers[8];
    if (ncolors > 8)
        return error_set(err, "at most 8 colour outputs per framebuffer (got %d)", ncolors);
    for (int i = 0; i < 8; i++)
        gl.NamedFramebufferTexture(fb->id, GL_COLOR_ATTACHMENT0 + (GLenum)i, 0, 0);
    for (int i = 0; i < ncolors; i++) {
        GLenum attachment = GL_COLOR_ATTACHMENT0 + (GLenum)i;
        if (color_layers && color_layers[i] >= 0)
            gl.NamedFramebufferTextureLayer(fb->id, attachment, colors[i]->id, 0, color_layers[i]);
        else
            gl.NamedFramebufferTexture(fb->id, attachment, colors[i]->id, 0);
        buffers[i] = attachment;
    }
    if (depth) {
        if (depth_layer >= 0)
            gl.NamedFramebufferTextureLayer(fb->id, GL_DEPTH_ATTACHMENT, depth->id, 0, depth_layer);
        else
            gl.NamedFramebufferTexture(fb->id, GL_DEPTH_ATTACHMENT, depth->id, 0);
    } else {
        gl.NamedFramebufferTexture(fb->id, GL_DEPTH_ATTACHMENT, 0, 0);
    }
    if (ncolors > 0)
        gl.NamedFramebufferDrawBuffers(fb->id, ncolors, buffers);
    else
        gl.NamedFramebufferDrawBuffer(fb->id, GL_NONE);
    GLenum status = gl.CheckNamedFramebufferStatus(fb->id, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return error_set(err, "framebuffer incomplete (status 0x%04x)", (unsigned)status);
    return gl_check("framebuffer set-up", err);
}

void gl_texture_clear(const struct gl_texture *texture, const float rgba[4])
{
    gl.ClearTexImage(texture->id, 0, GL_RGBA, GL_FLOAT, rgba);
}

bool gl_texture_copy(struct gl_texture *to, const struct gl_texture *from, bool mips, struct error *err)
{
    if (!to->id || to->width != from->width || to->height != from->height || to->format != from->format) {
        gl_texture_destroy(to);
        if (!gl_texture_create_levels(to, GL_TEXTURE_2D, from->format, from->width, from->height, 1, mips ? 0 : 1,
                                      err))
            return false;
    }
    gl.CopyImageSubData(from->id, GL_TEXTURE_2D, 0, 0, 0, 0, to->id, GL_TEXTURE_2D, 0, 0, 0, 0, from->width,
                        from->height, 1);
    if (mips)
        gl.GenerateTextureMipmap(to->id);
    return true;
}
