# ruff: noqa: F821  (the runner injects the thesis commands)
# parameters arrive as globals (and in current_run().parameters)
count = int(globals().get("count", 3))
height = float(globals().get("height", 0.0))
for i in range(count):
    createVertex((float(i), height, 0.0))
