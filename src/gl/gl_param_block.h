/* A pass's parameters as one std140 uniform block (issue 54), as `Frame`
 * is the frame's: a C struct mirrors the block, `members` names each of its
 * fields with the field's offsetof, and one upload a frame replaces a
 * look-up by name and a glProgramUniform call per value. Every program that
 * binds the block has its layout held to the mirror once (a member either
 * side lacks, or at another offset, is an error naming the shader, the block
 * and the member: gl_program_check_block). A pass's shaders declare the
 * block in one file its stages include (`beam_caustics/beams.glsl`). */
#ifndef CAUSTICA_GL_PARAM_BLOCK_H
#define CAUSTICA_GL_PARAM_BLOCK_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"
#include "gl/gl_program.h"

/* A uniform block member as the C struct that mirrors the block has it:
 * its name in the shader and offsetof in the struct (issue 54: a pass's
 * parameters as one block, uploaded in one call, as `Frame` is). */
struct gl_block_member {
    const char *name;
    size_t offset;
};

/* Whether `p`'s uniform block `block` is laid out as its C mirror: the
 * block holds exactly these `count` members, each at its offset, in at most
 * `size` bytes. An error names the program's shader, the block and what
 * differs (a member C has and the shader lacks, or the other way round, or
 * an offset). */
bool gl_program_check_block(const struct gl_program *p, const char *block, const struct gl_block_member *members,
                            int count, size_t size, struct error *err);

#define GL_PARAM_BLOCK_PROGRAMS 16 /* programs one block remembers as checked */

struct gl_param_block {
    const char *name;                      /* the block's name in GLSL ("BeamParams") */
    const struct gl_block_member *members; /* the C mirror's fields */
    int count;
    size_t size;                           /* sizeof the mirror (a multiple of 16) */
    GLuint buffer;                         /* made on the first upload; gl_param_block_release frees it */
    GLuint checked[GL_PARAM_BLOCK_PROGRAMS]; /* programs (GL names) whose layout matched ... */
    int units[GL_PARAM_BLOCK_PROGRAMS];      /* ... and the binding point each gave the block */
    int checked_count;
};

/* A block named `block_name` in GLSL, mirrored by C type `mirror` whose
 * fields the array `fields` lists: what a pass's create sets. */
#define GL_PARAM_BLOCK_OF(block_name, fields, mirror)                                                          \
    ((struct gl_param_block){.name = (block_name), .members = (fields),                                        \
                             .count = (int)(sizeof(fields) / sizeof((fields)[0])), .size = sizeof(mirror)})

/* Copies `values` (a mirror of `size` bytes) into the block's buffer. */
bool gl_param_block_upload(struct gl_param_block *b, const void *values, struct error *err);
/* Binds the buffer to `program`'s block, checking the layout and finding
 * its binding point the first time the program is seen (no look-up by name
 * after that). */
bool gl_param_block_bind(struct gl_param_block *b, const struct gl_program *program, struct error *err);
void gl_param_block_release(struct gl_param_block *b);

#endif
