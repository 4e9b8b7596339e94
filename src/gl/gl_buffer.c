#include "gl/gl_buffer.h"

bool gl_buffer_create(GLuint *buffer, const void *data, size_t bytes, GLbitfield flags, struct error *err)
{
    *buffer = 0;
    gl.CreateBuffers(1, buffer);
    gl.NamedBufferStorage(*buffer, (GLsizeiptr)(bytes ? bytes : 4), data, flags);
    if (!gl_check("creating a buffer", err)) {
        gl_buffer_destroy(buffer);
        return false;
    }
    return true;
}

bool gl_buffer_update(GLuint buffer, const void *data, size_t bytes, struct error *err)
{
    gl.NamedBufferSubData(buffer, 0, (GLsizeiptr)bytes, data);
    return gl_check("updating a buffer", err);
}

bool gl_buffer_read(GLuint buffer, void *out, size_t bytes, struct error *err)
{
    gl.GetNamedBufferSubData(buffer, 0, (GLsizeiptr)bytes, out);
    return gl_check("reading a buffer back", err);
}

void gl_buffer_destroy(GLuint *buffer)
{
    if (*buffer && gl_api_ready())
        gl.DeleteBuffers(1, buffer);
    *buffer = 0;
}
