# ruff: noqa: F821  (the runner injects the commands; the error is on line 7)
createVertex((0, 0, 0))
createVertex((1, 0, 0))


def broken():
    return deleteEdge(12345)


broken()
