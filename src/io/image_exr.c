/* OpenEXR files through OpenEXR's own C API (OpenEXRCore, Debian's
 * libopenexr-dev): the format renderers and compositors exchange linear
 * float images in, with named layers for extra outputs (the AOVs Mogwai and
 * Blender write beside the beauty image). Written as 32-bit float RGBA
 * scanlines with ZIP compression, atomically (a temporary renamed into
 * place); read: the R, G, B (and A) channels of the first part. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openexr.h>

#include "core/fileio.h"
#include "io/image.h"

bool image_path_is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && (strcmp(path + n - 4, ".exr") == 0 || strcmp(path + n - 4, ".EXR") == 0);
}

/* OpenEXR's own messages (it would print them on stderr before caustica's
 * line): kept for that one line instead, with the system's reason where it
 * gives one (a full disk). One image is read or written at a time. */
static char exr_last_message[512];

static void exr_keep_message(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt, (void)code;
    snprintf(exr_last_message, sizeof exr_last_message, "%s", msg ? msg : "");
}

static void exr_initializer(exr_context_initializer_t *init)
{
    exr_context_initializer_t defaults = EXR_DEFAULT_CONTEXT_INITIALIZER;
    *init = defaults;
    init->flags |= EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;
    init->error_handler_fn = exr_keep_message;
    exr_last_message[0] = '\0';
}

static bool exr_failed(exr_result_t rv, const char *path, const char *what, struct error *err)
{
    if (exr_last_message[0])
        return error_set(err, "%s: %s failed: %s (%s)", path, what, exr_get_default_error_message(rv),
                         exr_last_message);
    return error_set(err, "%s: %s failed: %s", path, what, exr_get_default_error_message(rv));
}

/* Which image and component a channel named "[layer.]C" reads. */
static bool channel_source(const char *name, const struct image *img, const struct image_layer *layers, int nlayers,
                           const struct image *surface, const float **base, int *component)
{
    const char *dot = strrchr(name, '.');
    const char *c = dot ? dot + 1 : name;
    static const char comps[] = "RGBA";
    /* the first surface's distance and object (image_exr_info.surface: G and B) */
    if (!dot && surface && (strcmp(name, "Z") == 0 || strcmp(name, "objectId") == 0)) {
        *base = surface->rgba;
        *component = name[0] == 'Z' ? 1 : 2;
        return true;
    }
    const char *k = c[0] == 'Z' ? comps : strchr(comps, c[0]); /* a depth layer's Z is its image's R */
    if (!k || !c[0] || c[1])
        return false;
    *component = (int)(k - comps);
    if (!dot) {
        *base = img->rgba;
        return true;
    }
    for (int i = 0; i < nlayers; i++)
        if (strlen(layers[i].name) == (size_t)(dot - name) && strncmp(layers[i].name, name, (size_t)(dot - name)) == 0) {
            *base = layers[i].image->rgba;
            return true;
        }
    return false;
}

/* Whether the first part has channels "layer.X"; false with a message
 * that names the layers it has (what `file.exr:LAYER` may ask for). */
static bool exr_has_layer(exr_const_context_t ctxt, const char *path, const char *layer, struct error *err)
{
    const exr_attr_chlist_t *channels = NULL;
    if (exr_get_channels(ctxt, 0, &channels) != EXR_ERR_SUCCESS || !channels)
        return true; /* the decoder says what is wrong */
    size_t prefix = strlen(layer);
    char names[1024] = "";
    size_t used = 0;
    int listed = 0;
    for (int32_t c = 0; c < channels->num_channels; c++) {
        const char *name = channels->entries[c].name.str;
        if (!name)
            continue;
        if (strncmp(name, layer, prefix) == 0 && name[prefix] == '.')
            return true;
        const char *dot = strrchr(name, '.');
        if (!dot)
            continue; /* the main image's R, G, B, A */
        int len = (int)(dot - name);
        if (len < 1)
            continue; /* ".R": no layer name to list (an empty one made the search below never advance) */
        char candidate[256];
        snprintf(candidate, sizeof candidate, "%.*s", len, name);
        size_t clen = strlen(candidate);
        bool seen = false; /* channels of one layer come together, sorted */
        for (const char *at = names; !seen && (at = strstr(at, candidate)) != NULL; at += clen)
            if ((at == names || at[-1] == ' ') && (at[clen] == ',' || at[clen] == '\0'))
                seen = true;
        if (!seen && used < sizeof names) {
            used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", listed ? ", " : "", candidate);
            listed++;
        }
    }
    return error_set(err, "%s: no layer '%s' (channels %s.R, %s.G, %s.B) in the EXR; %s%s", path, layer, layer, layer,
                     layer, listed ? "its layers: " : "it has no layers, only the image itself (R, G, B)", names);
}

/* The header's attributes besides the required ones (see image_exr_info). */
static exr_result_t write_attributes(exr_context_t ctxt, int part, const struct image_exr_info *info)
{
    /* Rec. 709 primaries and D65 white: sRGB's, the renderer's linear RGB */
    const exr_attr_chromaticities_t rec709 = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    exr_result_t rv = exr_attr_set_chromaticities(ctxt, part, "chromaticities", &rec709);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctxt, part, "software", "caustica " CAUSTICA_VERSION);
    if (!info)
        return rv;
    if (rv == EXR_ERR_SUCCESS && info->camera) {
        exr_attr_m44f_t to_camera, to_ndc;
        memcpy(to_camera.m, info->world_to_camera, sizeof to_camera.m);
        memcpy(to_ndc.m, info->world_to_ndc, sizeof to_ndc.m);
        rv = exr_attr_set_m44f(ctxt, part, "worldToCamera", &to_camera);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_attr_set_m44f(ctxt, part, "worldToNDC", &to_ndc);
    }
    if (rv == EXR_ERR_SUCCESS && info->fps > 0) {
        /* framesPerSecond as a rational: fps * 1000 / 1000 */
        exr_attr_rational_t fps = {(int32_t)(info->fps * 1000.0 + 0.5), 1000};
        rv = exr_attr_set_rational(ctxt, part, "framesPerSecond", &fps);
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_int(ctxt, part, "caustica:frame", info->frame);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_float(ctxt, part, "caustica:time", (float)info->time);
    if (rv == EXR_ERR_SUCCESS && info->scene)
        rv = exr_attr_set_string(ctxt, part, "caustica:scene", info->scene);
    if (rv == EXR_ERR_SUCCESS && info->renderer)
        rv = exr_attr_set_string(ctxt, part, "caustica:renderer", info->renderer);
    if (rv == EXR_ERR_SUCCESS && info->output)
        rv = exr_attr_set_string(ctxt, part, "caustica:output", info->output);
    return rv;
}

bool image_write_exr(const char *path, const struct image *img, const struct image_layer *layers, int nlayers,
                     const struct image_exr_info *info, struct error *err)
{
    for (int i = 0; i < nlayers; i++)
        if (layers[i].image->width != img->width || layers[i].image->height != img->height)
            return error_set(err, "%s: layer '%s' is %dx%d, the image %dx%d", path, layers[i].name,
                             layers[i].image->width, layers[i].image->height, img->width, img->height);
    char tmp[4200];
    /* made exclusively first (an unpredictable name, never a planted link), then OpenEXR writes it */
    int fd = path_temporary_create(path, tmp, sizeof tmp, err);
    if (fd < 0)
        return false;
    close(fd);
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init;
    exr_initializer(&init);
    exr_result_t rv = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv != EXR_ERR_SUCCESS) {
        remove(tmp);
        return exr_failed(rv, path, "opening for writing", err);
    }
    int part = 0;
    bool ok = true;
    const char *step = "";
    rv = exr_add_part(ctxt, "main", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, img->width, img->height, EXR_COMPRESSION_ZIP);
    static const char *const names[4] = {"R", "G", "B", "A"};
    /* the beauty channels as half floats on request: OpenEXR's encoder
     * converts the float pixels (round to nearest) as it packs them */
    exr_pixel_type_t beauty = info && info->half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    for (int c = 0; c < 4 && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctxt, part, names[c], beauty, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    for (int i = 0; i < nlayers && rv == EXR_ERR_SUCCESS; i++) {
        int channels = layers[i].depth ? 1 : layers[i].object_id ? 3 : 4;
        for (int c = 0; c < channels && rv == EXR_ERR_SUCCESS; c++) {
            char name[300];
            snprintf(name, sizeof name, "%s.%s", layers[i].name, layers[i].depth ? "Z" : names[c]);
            rv = exr_add_channel(ctxt, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
        }
    }
    /* the first surface of every object, glass and water included: Z (the
     * distance along the view axis, +inf where none) and objectId */
    if (info && info->surface) {
        if (info->surface->width != img->width || info->surface->height != img->height)
            rv = EXR_ERR_INVALID_ARGUMENT;
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_add_channel(ctxt, part, "Z", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_add_channel(ctxt, part, "objectId", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = write_attributes(ctxt, part, info);
    step = "defining the channels and attributes";
    if (rv == EXR_ERR_SUCCESS) {
        rv = exr_write_header(ctxt);
        step = "writing the header";
    }
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    size_t row = (size_t)img->width * 4 * sizeof(float);
    for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = started ? exr_encoding_update(ctxt, part, &chunk, &encoder)
                     : exr_encoding_initialize(ctxt, part, &chunk, &encoder);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (int c = 0; c < encoder.channel_count; c++) {
            exr_coding_channel_info_t *ch = &encoder.channels[c];
            const float *base = NULL;
            int component = 0;
            if (!channel_source(ch->channel_name, img, layers, nlayers, info ? info->surface : NULL, &base,
                                &component)) {
                rv = EXR_ERR_INVALID_ARGUMENT;
                break;
            }
            ch->encode_from_ptr = (const uint8_t *)(base + (size_t)chunk.start_y * (size_t)img->width * 4 +
                                                    (size_t)component);
            ch->user_pixel_stride = 4 * (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)row;
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (rv == EXR_ERR_SUCCESS && !started)
            rv = exr_encoding_choose_default_routines(ctxt, part, &encoder);
        started = true;
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &encoder);
        step = "writing the pixels";
    }
    if (started)
        exr_encoding_destroy(ctxt, &encoder);
    exr_result_t fin = exr_finish(&ctxt);
    if (rv == EXR_ERR_SUCCESS)
        rv = fin;
    ok = rv == EXR_ERR_SUCCESS;
    if (!ok) {
        remove(tmp);
        return exr_failed(rv, path, step, err);
    }
    if (rename(tmp, path) != 0) {
        remove(tmp);
        return error_set(err, "%s: cannot move the finished file into place", path);
    }
    return true;
}

/* Points the decoder's channels of `layer` (NULL: the top level) at the
 * image's rows of this chunk: R, G, B and A, or Z where the layer has no
 * colour (a depth layer, *depth_only); other channels are not read.
 * Whether any channel is read. */
static bool exr_route_channels(exr_decode_pipeline_t *decoder, const char *layer, struct image *img, int w,
                               int min_y, int start_y, bool *depth_only)
{
    bool found = false;
    size_t row = (size_t)w * 4 * sizeof(float);
    bool has_color = false;
    for (int c = 0; c < decoder->channel_count; c++) {
        const char *name = decoder->channels[c].channel_name;
        size_t prefix = layer ? strlen(layer) : 0;
        if (layer && (strncmp(name, layer, prefix) != 0 || name[prefix] != '.'))
            continue;
        name += layer ? prefix + 1 : 0;
        has_color |= (name[0] == 'R' || name[0] == 'G' || name[0] == 'B') && !name[1];
    }
    for (int c = 0; c < decoder->channel_count; c++) {
        exr_coding_channel_info_t *ch = &decoder->channels[c];
        const char *name = ch->channel_name;
        /* the layer's own channels: "R" at the top, "layer.R" in a layer */
        size_t prefix = layer ? strlen(layer) : 0;
        if (layer && (strncmp(name, layer, prefix) != 0 || name[prefix] != '.'))
            name = "";
        else if (layer)
            name += prefix + 1;
        static const char comps[] = "RGBA";
        /* Z is the image only where it has no colour (a depth layer); beside R, G, B (a
         * render's first-surface distance) it is left out */
        const char *k = NULL;
        if (name[0] && !name[1])
            k = name[0] == 'Z' ? (has_color ? NULL : comps) : strchr(comps, name[0]);
        if (k && name[0] == 'Z')
            *depth_only = true; /* a depth layer: Z into R, copied to G and B by the caller */
        if (!k || ch->x_samples != 1 || ch->y_samples != 1) {
            ch->decode_to_ptr = NULL; /* a layer or a subsampled channel: not read */
            continue;
        }
        found = true;
        ch->decode_to_ptr = (uint8_t *)(img->rgba + (size_t)(start_y - min_y) * (size_t)w * 4 +
                                        (size_t)(k - comps));
        ch->user_pixel_stride = 4 * (int32_t)sizeof(float);
        ch->user_line_stride = (int32_t)row;
        ch->user_bytes_per_element = 4;
        ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    return found;
}

bool image_read_exr_layer(const char *path, const char *layer, struct image *img, struct error *err)
{
    memset(img, 0, sizeof *img);
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init;
    exr_initializer(&init);
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS)
        return exr_failed(rv, path, "reading", err);
    exr_attr_box2i_t box;
    exr_storage_t storage;
    rv = exr_get_data_window(ctxt, 0, &box);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_storage(ctxt, 0, &storage);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(&ctxt);
        return exr_failed(rv, path, "reading the header", err);
    }
    if (layer && !exr_has_layer(ctxt, path, layer, err)) {
        exr_finish(&ctxt);
        return false;
    }
    int w = box.max.x - box.min.x + 1, h = box.max.y - box.min.y + 1;
    if (storage != EXR_STORAGE_SCANLINE) {
        exr_finish(&ctxt);
        return error_set(err, "%s: only scanline EXR files are read (this one is tiled or deep)", path);
    }
    if (w < 1 || h < 1 || w > 16384 || h > 16384) {
        exr_finish(&ctxt);
        return error_set(err, "%s: an EXR of %dx%d is out of range (1..16384)", path, w, h);
    }
    /* every chunk has an 8-byte entry in the offset table and at least an
     * 8-byte header (its line, its size): the file must hold them before a
     * w x h image is allocated (a 377-byte file claiming 16384^2 took 4 GB) */
    int32_t chunks = 0;
    struct stat st;
    rv = exr_get_chunk_count(ctxt, 0, &chunks);
    if (rv != EXR_ERR_SUCCESS || stat(path, &st) != 0 ||
        !image_check_header(path, w, h, 16ull * (unsigned long long)(chunks > 0 ? chunks : 1),
                            (unsigned long long)st.st_size, err)) {
        exr_finish(&ctxt);
        return rv != EXR_ERR_SUCCESS ? exr_failed(rv, path, "reading the chunk table", err) : false;
    }
    if (!image_create(img, w, h, err)) {
        exr_finish(&ctxt);
        return false;
    }
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        img->rgba[i * 4 + 3] = 1.0f; /* alpha 1 where the file has none */
    int32_t lines = 1;
    rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false, found = false, depth_only = false;
    for (int y = box.min.y; y <= box.max.y && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_read_scanline_chunk_info(ctxt, 0, y, &chunk);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = started ? exr_decoding_update(ctxt, 0, &chunk, &decoder)
                     : exr_decoding_initialize(ctxt, 0, &chunk, &decoder);
        if (rv != EXR_ERR_SUCCESS)
            break;
        found |= exr_route_channels(&decoder, layer, img, w, box.min.y, chunk.start_y, &depth_only);
        if (!started)
            rv = exr_decoding_choose_default_routines(ctxt, 0, &decoder);
        started = true;
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_decoding_run(ctxt, 0, &decoder);
    }
    if (started)
        exr_decoding_destroy(ctxt, &decoder);
    exr_finish(&ctxt);
    if (rv != EXR_ERR_SUCCESS) {
        image_destroy(img);
        return exr_failed(rv, path, "reading the pixels", err);
    }
    if (depth_only)
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            img->rgba[i * 4 + 1] = img->rgba[i * 4 + 2] = img->rgba[i * 4];
    if (!found) {
        image_destroy(img);
        return layer ? error_set(err, "%s: no layer '%s' (channels %s.R, %s.G, %s.B) in the EXR", path, layer, layer,
                                 layer, layer)
                     : error_set(err, "%s: no R, G or B channel in the EXR's first part", path);
    }
    return true;
}

bool image_read_exr(const char *path, struct image *img, struct error *err)
{
    return image_read_exr_layer(path, NULL, img, err);
}
