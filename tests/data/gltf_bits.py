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
