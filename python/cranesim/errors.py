"""The exceptions cranesim raises."""


class SceneError(ValueError):
    """A scene that cannot be read or compiled.

    The message names the file, the YAML path of the offending value and its line, as
    ``crane-sim`` prints them; the same are attributes: ``file``, ``path`` (e.g.
    ``members[3].length.limits``) and ``line`` (None where the value has no line: a scene
    given as a dict).
    """

    def __init__(self, file: str, path: str, line: int, message: str):
        super().__init__(f"{file}: {message}")
        self.file = file
        self.path = path
        self.line = line if line > 0 else None
