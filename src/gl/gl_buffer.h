/* GL buffer objects: creation with immutable storage, sub-data updates,
 * read-back, and the one release path. */
#ifndef CAUSTICA_GL_BUFFER_H
#define CAUSTICA_GL_BUFFER_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"
#include "gl/gl_api.h"

/* A buffer of `bytes` (at least 4: GL refuses empty storage) holding
 * `data` (may be NULL); `flags` as for glNamedBufferStorage
 * (GL_DYNAMIC_STORAGE_BIT for buffers updated with gl_buffer_update). */
bool gl_buffer_create(GLuint *buffer, const void *data, size_t bytes, GLbitfield flags, struct error *err);
bool gl_buffer_update(GLuint buffer, const void *data, size_t bytes, struct error *err);
bool gl_buffer_read(GLuint buffer, void *out, size_t bytes, struct error *err);
/* Deletes the buffer (when GL is up) and zeroes the name: safe twice. */
void gl_buffer_destroy(GLuint *buffer);

#endif
