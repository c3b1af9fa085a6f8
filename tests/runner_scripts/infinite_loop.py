# ruff: noqa: F821  (the runner injects the thesis commands)
createVertex((0, 0, 0))
while True:
    pass
