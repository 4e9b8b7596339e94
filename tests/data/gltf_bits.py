"""What the test-data writers here share (standard library only): a PNG
encoder and a data URI, so each make_*.py writes its glTF file alone."""
import base64, struct, zlib


def png(w, h, rows, alpha):
    """A PNG of w x h 8-bit texels: rows of RGB (alpha False) or RGBA values."""
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6 if alpha else 2, 0, 0, 0)) \
        + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def data_uri(mime, data):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def textured_quad(generator, material, image):
    """A glTF file of one 1 x 1 quad in the xz plane (y = 0, facing +y, x and
    z in -0.5..0.5, uv 0..1) of `material`, whose texture 0 is `image`
    (PNG bytes) sampled nearest."""
    pos = [-0.5, 0, -0.5, 0.5, 0, -0.5, 0.5, 0, 0.5, -0.5, 0, 0.5]
    nrm = [0, 1, 0] * 4
    uv = [0, 0, 1, 0, 1, 1, 0, 1]
    idx = [0, 2, 1, 0, 3, 2]
    buf = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
    return {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [material],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728}],
        "images": [{"uri": data_uri("image/png", image)}],
        "buffers": [{"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, 0, -0.5],
             "max": [0.5, 0, 0.5]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
