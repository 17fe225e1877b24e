#!/usr/bin/env python3
"""Writes the bundled SSD as test fixtures: in the other output layout, and at another input size.

jetson-inference's pytorch-ssd export (its train_ssd.py, then onnx_export.py) gives a model whose
input is `input_0`, (pixel - 127) / 128 in RGB planes, and whose outputs are already decoded:
`scores` [N, anchors, classes] (probabilities, column 0 the background) and `boxes`
[N, anchors, 4] (x1, y1, x2, y2 in 0..1). This script wraps the bundled model (box codes + class
logits, decoded against its anchors CSV) into that interface with ONNX nodes around the unchanged
network, and writes the sidecar description and a labels file of its own names, so that the same
detections are expected from both files:
  OUT.onnx          the wrapped network
  OUT.model.yaml    layout decoded, its input normalisation, its output names, its labels file
  OUT.labels.txt    BACKGROUND, then COCO's names with "person" renamed "pedestrian"

With a fifth argument SIZE it writes instead the bundled model fed SIZE x SIZE pixels, in the
bundled layout (box codes + logits):
  OUT.onnx          the network with its input resized, its TF "SAME" paddings recomputed for the
                    new feature map sizes, and its description inside (metadata rtmot.model)
  OUT.anchors.csv   anchors regenerated for the new feature maps by TF's SSD anchor generator,
                    which reproduces the bundled model's anchors file at 300 (checked here)
Usage: make_model_fixture.py MODEL.onnx ANCHORS.csv COCO_LABELS.txt OUT [SIZE]
  (OUT a path without suffix). Needs Debian's python3-onnx and python3-numpy (as
  scripts/fetch_model.sh).
"""
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


def constant(graph, name, values):
    graph.initializer.append(numpy_helper.from_array(np.asarray(values, dtype=np.float32), name))
    return name


def main(model_path, anchors_path, coco_labels_path, out):
    model = onnx.load(model_path)
    graph = model.graph
    anchors = np.loadtxt(anchors_path, delimiter=",", comments="#", dtype=np.float32)  # yc,xc,h,w
    count = anchors.shape[0]

    # Input: (p - 127) / 128 -> the network's (p - 127.5) / 127.5.
    old_input = graph.input[0].name
    new_input = "input_0"
    for node in graph.node:
        for i, name in enumerate(node.input):
            if name == old_input:
                node.input[i] = "converted_input"
    graph.input[0].name = new_input
    nodes = [
        helper.make_node("Mul", [new_input, constant(graph, "in_scale", 128.0 / 127.5)], ["in_scaled"]),
        helper.make_node("Add", ["in_scaled", constant(graph, "in_shift", -0.5 / 127.5)],
                         ["converted_input"]),
    ]
    rest = list(graph.node)
    del graph.node[:]
    graph.node.extend(nodes + rest)

    # Outputs: box codes (ty, tx, th, tw), scales 10, 10, 5, 5, against the anchors -> corners.
    def column(source, k, name):
        starts = constant(graph, name + "_starts", [k])
        ends = constant(graph, name + "_ends", [k + 1])
        axes = constant(graph, name + "_axes", [2])
        for c in (starts, ends, axes):  # Slice's indices are int64
            init = next(i for i in graph.initializer if i.name == c)
            init.CopyFrom(numpy_helper.from_array(numpy_helper.to_array(init).astype(np.int64), c))
        return helper.make_node("Slice", [source, starts, ends, axes], [name])

    def per_anchor(name, values):
        return constant(graph, name, np.asarray(values, dtype=np.float32).reshape(1, count, 1))

    tail = [
        column("box_encodings", 0, "ty"), column("box_encodings", 1, "tx"),
        column("box_encodings", 2, "th"), column("box_encodings", 3, "tw"),
        helper.make_node("Mul", ["ty", per_anchor("ha10", anchors[:, 2] / 10)], ["ty_s"]),
        helper.make_node("Add", ["ty_s", per_anchor("ya", anchors[:, 0])], ["yc"]),
        helper.make_node("Mul", ["tx", per_anchor("wa10", anchors[:, 3] / 10)], ["tx_s"]),
        helper.make_node("Add", ["tx_s", per_anchor("xa", anchors[:, 1])], ["xc"]),
        helper.make_node("Mul", ["th", constant(graph, "fifth", 0.2)], ["th_s"]),
        helper.make_node("Exp", ["th_s"], ["th_e"]),
        helper.make_node("Mul", ["th_e", per_anchor("ha_half", anchors[:, 2] / 2)], ["half_h"]),
        helper.make_node("Mul", ["tw", constant(graph, "fifth_w", 0.2)], ["tw_s"]),
        helper.make_node("Exp", ["tw_s"], ["tw_e"]),
        helper.make_node("Mul", ["tw_e", per_anchor("wa_half", anchors[:, 3] / 2)], ["half_w"]),
        helper.make_node("Sub", ["xc", "half_w"], ["x1"]),
        helper.make_node("Sub", ["yc", "half_h"], ["y1"]),
        helper.make_node("Add", ["xc", "half_w"], ["x2"]),
        helper.make_node("Add", ["yc", "half_h"], ["y2"]),
        helper.make_node("Concat", ["x1", "y1", "x2", "y2"], ["boxes"], axis=2),
        helper.make_node("Sigmoid", ["class_logits"], ["scores"]),
    ]
    graph.node.extend(tail)
    classes = next(o for o in graph.output if o.name == "class_logits")
    columns = classes.type.tensor_type.shape.dim[2].dim_value
    del graph.output[:]
    graph.output.extend([
        helper.make_tensor_value_info("scores", TensorProto.FLOAT, ["batch", count, columns]),
        helper.make_tensor_value_info("boxes", TensorProto.FLOAT, ["batch", count, 4]),
    ])
    onnx.checker.check_model(model)
    onnx.save(model, out + ".onnx")

    with open(coco_labels_path) as f:
        coco = [line.rstrip("\n") for line in f]
    labels = ["BACKGROUND"] + [("pedestrian" if name == "person" else name or f"reserved-{k}") for k, name in enumerate(coco[1:], start=1)]
    assert len(labels) == columns, (len(labels), columns)
    with open(out + ".labels.txt", "w") as f:
        f.write("\n".join(labels) + "\n")
    stem = out.rsplit("/", 1)[-1]
    with open(out + ".model.yaml", "w") as f:
        f.write(f"""# {stem}: the bundled SSD wrapped as jetson-inference's pytorch-ssd export is
layout: decoded
input:
  size: 300
  colour: rgb
  mean: 127
  scale: 0.0078125
outputs:
  scores: scores
  boxes: boxes
labels: {stem}.labels.txt
""")


# SSDLite-MobileNetV2 COCO's anchor generator (TF Object Detection API, ssd_anchor_generator in
# its pipeline config): 6 layers, scales 0.2..0.95, aspect ratios 1, 2, 1/2, 3, 1/3 plus one box
# between this layer's scale and the next's; the lowest layer reduced to 3 boxes.
ANCHOR_LAYERS = 6
MIN_SCALE, MAX_SCALE = 0.2, 0.95
ASPECT_RATIOS = (1.0, 2.0, 0.5, 3.0, 0.3333)


def ssd_anchors(grid_sizes):
    """Rows (ycenter, xcenter, height, width) in 0..1, in the order the heads emit them: layer by
    layer, row-major over the grid, box specs innermost."""
    scales = [MIN_SCALE + (MAX_SCALE - MIN_SCALE) * i / (ANCHOR_LAYERS - 1)
              for i in range(ANCHOR_LAYERS)] + [1.0]
    rows = []
    for layer, grid in enumerate(grid_sizes):
        scale, next_scale = scales[layer], scales[layer + 1]
        if layer == 0:
            specs = [(0.1, 1.0), (scale, 2.0), (scale, 0.5)]
        else:
            specs = [(scale, ratio) for ratio in ASPECT_RATIOS] + [(np.sqrt(scale * next_scale), 1.0)]
        stride = 1.0 / grid
        for y in range(grid):
            for x in range(grid):
                for box_scale, ratio in specs:
                    rows.append(((y + 0.5) * stride, (x + 0.5) * stride,
                                 box_scale / np.sqrt(ratio), box_scale * np.sqrt(ratio)))
    return np.asarray(rows, dtype=np.float64)


def same_pads(size, kernel, stride):
    """TF's "SAME" padding (begin, end) of one spatial axis, and the output size."""
    out = -(-size // stride)
    total = max((out - 1) * stride + kernel - size, 0)
    return total // 2, total - total // 2, out


def resize_network(graph, size):
    """Feeds the network size x size: every Conv's padding recomputed as TF's "SAME" for its new
    input (the exported pads are SAME's for 300, and SAME pads depend on the input's parity).
    Returns each head's grid size, in head order."""
    spatial = {graph.input[0].name: (300, size)}  # name -> (size at 300, size now)
    heads = {}
    for node in graph.node:
        if node.op_type == "Conv":
            before, now = spatial[node.input[0]]
            attrs = {a.name: a for a in node.attribute}
            kernel, stride = attrs["kernel_shape"].ints[0], attrs["strides"].ints[0]
            pb, pe, out_before = same_pads(before, kernel, stride)
            assert list(attrs["pads"].ints) == [pb, pb, pe, pe], (node.name, attrs["pads"].ints)
            pb, pe, out_now = same_pads(now, kernel, stride)
            del attrs["pads"].ints[:]
            attrs["pads"].ints.extend([pb, pb, pe, pe])
            spatial[node.output[0]] = (out_before, out_now)
            head = node.name.split("/")[0]
            if head.startswith("BoxPredictor_") and head not in heads:
                heads[head] = now
        elif node.op_type in ("Clip", "Relu", "Add", "Identity") and node.input[0] in spatial:
            spatial[node.output[0]] = spatial[node.input[0]]
    dims = graph.input[0].type.tensor_type.shape.dim
    dims[2].dim_value = size
    dims[3].dim_value = size
    return [heads[f"BoxPredictor_{i}"] for i in range(ANCHOR_LAYERS)]


def write_resized(model_path, anchors_path, out, size):
    bundled = np.loadtxt(anchors_path, delimiter=",", comments="#", dtype=np.float64)
    generated = ssd_anchors([19, 10, 5, 3, 2, 1])
    assert generated.shape == bundled.shape, (generated.shape, bundled.shape)
    assert np.abs(generated - bundled).max() < 1e-6, np.abs(generated - bundled).max()

    model = onnx.load(model_path)
    grids = resize_network(model.graph, size)
    anchors = ssd_anchors(grids)
    for output in model.graph.output:
        output.type.tensor_type.shape.dim[1].dim_value = anchors.shape[0]
    stem = out.rsplit("/", 1)[-1]
    description = f"""# {stem}: the bundled SSD fed {size} x {size}; anchors {stem}.anchors.csv
layout: deltas
input:
  size: {size}
"""
    entry = model.metadata_props.add()
    entry.key, entry.value = "rtmot.model", description
    onnx.checker.check_model(model)
    onnx.save(model, out + ".onnx")
    with open(out + ".anchors.csv", "w") as f:
        f.write(f"# SSD anchors of {stem} (grids {grids}): ycenter,xcenter,height,width (0..1)\n")
        for row in anchors:
            f.write(",".join(f"{v:.9g}" for v in row) + "\n")


if __name__ == "__main__":
    if len(sys.argv) == 6:
        write_resized(sys.argv[1], sys.argv[2], sys.argv[4], int(sys.argv[5]))
    elif len(sys.argv) == 5:
        main(*sys.argv[1:])
    else:
        sys.exit(__doc__)
