"""The scene's error: a malformed scene, said before any work is done."""


class SceneError(ValueError):
    """A scene is malformed; the message says which field, what was received and what is accepted."""
