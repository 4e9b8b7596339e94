/* A pass's parameters as one uniform block (see gl_param_block.h). */
#include "gl/gl_param_block.h"

#include "gl/gl_buffer.h"

/* A program's block against its C mirror (gl_param_block.h). */
bool gl_program_check_block(const struct gl_program *p, const char *block, const struct gl_block_member *members,
                            int count, size_t size, struct error *err)
{
    const char *stage = p->stages[1][0] ? p->stages[1] : p->stages[0][0] ? p->stages[0] : p->stages[2];
    GLuint b = gl.GetProgramResourceIndex(p->id, GL_UNIFORM_BLOCK, block);
    if (b == GL_INVALID_INDEX)
        return error_set(err, "%s: no uniform block '%s' (its C mirror has %d members)", stage, block, count);
    static const GLenum block_props[2] = {GL_BUFFER_DATA_SIZE, GL_NUM_ACTIVE_VARIABLES};
    GLint bv[2] = {0, 0};
    gl.GetProgramResourceiv(p->id, GL_UNIFORM_BLOCK, b, 2, block_props, 2, NULL, bv);
    for (int i = 0; i < count; i++) {
        GLuint m = gl.GetProgramResourceIndex(p->id, GL_UNIFORM, members[i].name);
        static const GLenum props[2] = {GL_OFFSET, GL_BLOCK_INDEX};
        GLint v[2] = {-1, -1};
        if (m != GL_INVALID_INDEX)
            gl.GetProgramResourceiv(p->id, GL_UNIFORM, m, 2, props, 2, NULL, v);
        if (m == GL_INVALID_INDEX || v[1] != (GLint)b)
            return error_set(err, "%s: uniform block '%s' has no member '%s', which its C mirror sets", stage, block,
                             members[i].name);
        if ((size_t)v[0] != members[i].offset)
            return error_set(err, "%s: uniform block '%s': member '%s' at byte %d, its C mirror's at %zu", stage,
                             block, members[i].name, v[0], members[i].offset);
    }
    if (bv[1] != count)
        return error_set(err, "%s: uniform block '%s' has %d members, its C mirror %d", stage, block, bv[1], count);
    if ((size_t)bv[0] > size)
        return error_set(err, "%s: uniform block '%s' takes %d bytes, its C mirror %zu", stage, block, bv[0], size);
    return true;
}

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
