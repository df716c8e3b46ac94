"""The exception every m4mesh call raises on bad input or a bad stream."""


class Error(Exception):
    """An m4mesh error: what was wrong, where.

    Attributes:
        kind: the class of error ("truncated", "out-of-range", "structure", "usage", …).
        element: the syntax element read or written when it happened ("" when none).
        frame: the frame (3D) or plane (2D) it concerns, or -1.
        offset: the bit offset in the stream, or -1.
        message: the message alone; str(error) adds frame, element and offset.
    """

    def __init__(self, text, kind="", element="", frame=-1, offset=-1, message=""):
        super().__init__(text)
        self.kind = kind
        self.element = element
        self.frame = frame
        self.offset = offset
        self.message = message or text
