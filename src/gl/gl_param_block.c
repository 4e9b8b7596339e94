/* A pass's parameters as one uniform block (see gl_param_block.h). */
#include "gl/gl_param_block.h"

#include "gl/gl_buffer.h"

bool gl_param_block_upload(struct gl_param_block *b, const void *values, struct error *err)
{
    if (!b->buffer && !gl_buffer_create(&b->buffer, NULL, b->size, GL_DYNAMIC_STORAGE_BIT, err))
        return false;
    return gl_buffer_update(b->buffer, values, b->size, err);
}

bool gl_param_block_bind(struct gl_param_block *b, const struct gl_program *program, struct error *err)
{
    int at = -1;
    for (int i = 0; i < b->checked_count && at < 0; i++)
        if (b->checked[i] == program->id)
            at = i;
    if (at < 0) {
        if (!gl_program_check_block(program, b->name, b->members, b->count, b->size, err))
            return false;
        /* a full list starts again (a pass with more programs checks some twice) */
        if (b->checked_count == GL_PARAM_BLOCK_PROGRAMS)
            b->checked_count = 0;
        at = b->checked_count++;
        b->checked[at] = program->id;
        b->units[at] = gl_program_unit(program, GL_SLOT_UNIFORM_BLOCK, b->name);
    }
    gl_program_bind_uniform_block_unit(b->units[at], b->buffer);
    return true;
}

void gl_param_block_release(struct gl_param_block *b)
{
    gl_buffer_destroy(&b->buffer);
    b->checked_count = 0;
}
