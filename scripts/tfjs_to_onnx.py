#!/usr/bin/env python3
"""Converts the TensorFlow.js graph model of COCO SSDLite-MobileNetV2 to ONNX for OpenCV DNN.

Keeps only the network proper: from the normalised image (the output of the graph's Preprocessor)
to the raw box encodings and class logits. The Preprocessor (a TensorArray while-loop that resizes
and scales) and the Postprocessor (box decoding, sigmoid, slicing) are cut: OpenCV 4.6 cannot run
them, and the C++ detector does them (see docs/model.md). The anchors the Postprocessor decodes
against are written to a CSV beside the model.

The batch dimension is dynamic ("batch"): OpenCV runs N images in one forward pass and the outputs
are [N, 1917, 4] and [N, 1917, 91], one row block per image.

Batch norms and bias adds are folded into the convolutions; TF 'SAME' padding becomes explicit
(asymmetric where TF pads more at the end). Only the ops this graph uses are supported: anything
else is an error naming the node, so a different model cannot be half-converted silently.

Usage: tfjs_to_onnx.py MODEL_JSON OUT_ONNX OUT_ANCHORS_CSV
Needs Debian's python3-onnx and python3-numpy.
"""
import json
import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

INPUT_NODE = "Preprocessor/sub"  # the image after resize and scaling to [-1, 1], NHWC 1x300x300x3
BOX_NODE = "concat"  # box encodings [1, 1917, 1, 4] (ty, tx, th, tw)
CLASS_NODE = "concat_1"  # class logits [1, 1917, 91], background first
ANCHOR_NODE = "Postprocessor/ExpandDims"  # [1, 1917, 4] anchors (ymin, xmin, ymax, xmax), 0..1
INPUT_SIZE = 300
BATCH = "batch"  # a symbolic (dynamic) batch dimension: one forward pass takes N images


class ConversionError(Exception):
    pass


def load_tfjs(model_json_path):
    with open(model_json_path) as f:
        model = json.load(f)
    folder = os.path.dirname(model_json_path)
    weights = {}
    for group in model["weightsManifest"]:
        blob = b"".join(open(os.path.join(folder, p), "rb").read() for p in group["paths"])
        offset = 0
        for spec in group["weights"]:
            if "quantization" in spec:
                raise ConversionError(f"weight {spec['name']}: quantized weights are not supported")
            dtype = {"float32": np.float32, "int32": np.int32}[spec["dtype"]]
            count = int(np.prod(spec["shape"])) if spec["shape"] else 1
            size = count * 4
            if offset + size > len(blob):
                raise ConversionError(f"weight shards too short for {spec['name']}: truncated download?")
            weights[spec["name"]] = np.frombuffer(blob, dtype, count, offset).reshape(spec["shape"])
            offset += size
        if offset != len(blob):
            raise ConversionError(f"weight shards hold {len(blob) - offset} bytes more than the manifest")
    nodes = {n["name"]: n for n in model["modelTopology"]["node"]}
    return nodes, weights


def strip(name):
    return name.split(":")[0].lstrip("^")


class Graph:
    """Lazy values so that per-channel Mul/Add/BatchNorm after a convolution fold into it."""

    def __init__(self, nodes, weights):
        self.nodes = nodes
        self.weights = weights
        self.onnx_nodes = []
        self.initializers = []
        self.memo = {}
        self.consumers = {}
        for n in nodes.values():
            for i in n.get("input", []):
                self.consumers[strip(i)] = self.consumers.get(strip(i), 0) + 1
        self.counter = 0

    # ---- constants
    def const(self, name):
        if name in self.weights:
            return self.weights[name]
        node = self.nodes[name]
        if node["op"] != "Const":
            return None
        t = node["attr"]["value"]["tensor"]
        dims = [int(d["size"]) for d in t.get("tensorShape", {}).get("dim", [])]
        vals = t.get("intVal") or t.get("floatVal")
        if not vals:
            raise ConversionError(f"constant {name} has no value")
        return np.array(vals).reshape(dims) if dims else np.array(vals[0])

    def is_const(self, name):
        return name in self.weights or self.nodes[name]["op"] == "Const"

    def add_init(self, array, hint):
        self.counter += 1
        name = f"{hint}_{self.counter}"
        self.initializers.append(numpy_helper.from_array(np.ascontiguousarray(array), name))
        return name

    def emit(self, op, inputs, name, **attrs):
        self.onnx_nodes.append(helper.make_node(op, inputs, [name], name=name, **attrs))
        return name

    # ---- values: ("tensor", onnx_name, (C, H, W)), conv dicts, sums
    def value(self, name):
        name = strip(name)
        if name not in self.memo:
            self.memo[name] = self.convert(self.nodes[name])
        return self.memo[name]

    def single_use(self, name):
        return self.consumers.get(strip(name), 0) == 1

    def convert(self, node):
        op, name, inputs = node["op"], node["name"], node.get("input", [])
        attr = node.get("attr", {})
        if name == INPUT_NODE:
            return {"kind": "tensor", "name": "image", "shape": (3, INPUT_SIZE, INPUT_SIZE)}
        if op in ("Conv2D", "DepthwiseConv2dNative"):
            return self.conv(node, depthwise=(op == "DepthwiseConv2dNative"))
        if op in ("Mul", "Add", "BiasAdd", "AddN"):
            return self.arithmetic(node)
        if op == "FusedBatchNorm":
            x = self.value(inputs[0])
            if x["kind"] != "conv" or not self.single_use(inputs[0]):
                raise ConversionError(f"{name}: batch norm not after a convolution")
            gamma, beta, mean, var = (self.const(strip(i)) for i in inputs[1:5])
            scale = gamma / np.sqrt(var + attr["epsilon"]["f"])
            return self.scaled(x, scale, (x["B"] - mean) * scale + beta)
        if op == "Relu6":
            # Opset 10's Clip (bounds as attributes): OpenCV 4.6 maps it to ReLU6, and rejects the
            # opset-11 form with bounds as inputs.
            x = self.tensor(self.value(inputs[0]))
            return {"kind": "tensor", "name": self.emit("Clip", [x["name"]], name, min=0.0, max=6.0),
                    "shape": x["shape"]}
        if op == "Reshape":
            # Predictor head NHWC [N,H,W,A*K] -> [N, H*W*A, K]: NCHW needs the transpose first.
            # The 0 keeps the batch dimension (ONNX Reshape: 0 copies the input's dimension), so a
            # batch of N images gives N rows of anchors; a 1 here would concatenate them.
            x = self.tensor(self.value(inputs[0]))
            shape_node = self.nodes[strip(inputs[1])]
            k = int(self.const(strip(shape_node["input"][-1])))
            t = self.emit("Transpose", [x["name"]], name + "/nhwc", perm=[0, 2, 3, 1])
            shape = self.add_init(np.array([0, -1, k], np.int64), "shape")
            return {"kind": "flat", "name": self.emit("Reshape", [t, shape], name)}
        if op == "ConcatV2":
            parts = [self.value(i) for i in inputs[:-1]]
            if any(p["kind"] != "flat" for p in parts) or int(self.const(strip(inputs[-1]))) != 1:
                raise ConversionError(f"{name}: only the predictor concatenation is supported")
            return {"kind": "flat", "name": self.emit("Concat", [p["name"] for p in parts], name,
                                                      axis=1)}
        raise ConversionError(f"node {name}: op {op} is not supported by this converter")

    def conv(self, node, depthwise):
        attr = node["attr"]
        x = self.tensor(self.value(node["input"][0]))
        w = self.const(strip(node["input"][1])).astype(np.float32)
        if attr.get("data_format", {}).get("s") not in (None, list(b"NHWC")):
            raise ConversionError(f"{node['name']}: only NHWC is supported")
        kh, kw = w.shape[0], w.shape[1]
        if depthwise:  # TF [kh, kw, C, 1] -> ONNX [C, 1, kh, kw], one group per channel
            if w.shape[3] != 1:
                raise ConversionError(f"{node['name']}: depth multiplier must be 1")
            w = w.transpose(2, 3, 0, 1)
            groups, out_c = w.shape[0], w.shape[0]
        else:  # TF [kh, kw, in, out] -> ONNX [out, in, kh, kw]
            w = w.transpose(3, 2, 0, 1)
            groups, out_c = 1, w.shape[0]
        stride = int(attr["strides"]["list"]["i"][1])
        dil = attr.get("dilations", {}).get("list", {}).get("i", ["1"] * 4)
        if any(int(d) != 1 for d in dil):
            raise ConversionError(f"{node['name']}: dilation is not supported")
        padding = bytes(attr["padding"]["s"]).decode()
        _, h, wd = x["shape"]
        pads, out = [], []
        for size, k in ((h, kh), (wd, kw)):
            if padding == "SAME":
                o = -(-size // stride)
                total = max((o - 1) * stride + k - size, 0)
                pads.append((total // 2, total - total // 2))  # TF puts the odd pixel at the end
            elif padding == "VALID":
                o = (size - k) // stride + 1
                pads.append((0, 0))
            else:
                raise ConversionError(f"{node['name']}: padding {padding}")
            out.append(o)
        return {"kind": "conv", "x": x, "W": w, "B": np.zeros(out_c, np.float32), "name": node["name"],
                "attrs": dict(kernel_shape=[kh, kw], strides=[stride, stride], group=groups,
                              pads=[pads[0][0], pads[1][0], pads[0][1], pads[1][1]]),
                "shape": (out_c, out[0], out[1])}

    def scaled(self, conv, scale, bias):
        w = conv["W"] * scale.reshape(-1, 1, 1, 1).astype(np.float32)
        return dict(conv, W=w.astype(np.float32), B=bias.astype(np.float32))

    def arithmetic(self, node):
        op, name, inputs = node["op"], node["name"], node["input"]
        consts = [i for i in inputs if self.is_const(strip(i))]
        others = [i for i in inputs if not self.is_const(strip(i))]
        if len(consts) == 1 and len(others) == 1:
            c = self.const(strip(consts[0])).astype(np.float32)
            x = self.value(others[0])
            single = self.single_use(others[0])
            if op == "Mul" and x["kind"] == "conv" and single:
                return self.scaled(x, np.broadcast_to(c, x["B"].shape), x["B"] * c)
            if op in ("Add", "BiasAdd") and x["kind"] == "conv" and single:
                return dict(x, B=(x["B"] + c).astype(np.float32))
            if op == "Add" and x["kind"] == "sum" and single:
                return dict(x, bias=x["bias"] + c)
            raise ConversionError(f"{name}: {op} with a constant that cannot be folded")
        if not consts and op in ("Add", "AddN"):
            terms = [self.value(i) for i in others]
            return {"kind": "sum", "terms": terms, "bias": np.zeros(terms[0]["shape"][0], np.float32),
                    "name": name, "shape": terms[0]["shape"]}
        raise ConversionError(f"{name}: unsupported {op} of {inputs}")

    def tensor(self, v):
        """Materialises a lazy value as an ONNX tensor."""
        if v["kind"] == "tensor":
            return v
        if v.get("done"):
            return v["done"]
        if v["kind"] == "conv":
            w = self.add_init(v["W"], "W")
            b = self.add_init(v["B"], "B")
            out = self.emit("Conv", [v["x"]["name"], w, b], v["name"], **v["attrs"])
        elif v["kind"] == "sum":
            terms = list(v["terms"])
            conv_at = next((i for i, t in enumerate(terms) if t["kind"] == "conv"), None)
            if conv_at is None:
                raise ConversionError(f"{v['name']}: sum without a convolution to take its bias")
            terms[conv_at] = dict(terms[conv_at], B=terms[conv_at]["B"] + v["bias"])
            names = [self.tensor(t)["name"] for t in terms]
            out = names[0]
            for i, n in enumerate(names[1:]):
                out = self.emit("Add", [out, n], f"{v['name']}/{i}")
        else:
            raise ConversionError(f"cannot materialise {v['kind']}")
        v["done"] = {"kind": "tensor", "name": out, "shape": v["shape"]}
        return v["done"]


def convert(model_json, out_onnx, out_anchors):
    nodes, weights = load_tfjs(model_json)
    g = Graph(nodes, weights)
    boxes, classes = g.value(BOX_NODE), g.value(CLASS_NODE)
    g.emit("Identity", [boxes["name"]], "box_encodings")
    g.emit("Identity", [classes["name"]], "class_logits")
    anchors = weights[ANCHOR_NODE].reshape(-1, 4)
    num = anchors.shape[0]
    graph = helper.make_graph(
        g.onnx_nodes, "ssdlite_mobilenet_v2_coco",
        [helper.make_tensor_value_info("image", TensorProto.FLOAT, [BATCH, 3, INPUT_SIZE, INPUT_SIZE])],
        [helper.make_tensor_value_info("box_encodings", TensorProto.FLOAT, [BATCH, num, 4]),
         helper.make_tensor_value_info("class_logits", TensorProto.FLOAT, [BATCH, num, 91])],
        g.initializers)
    model = helper.make_model(graph, producer_name="rtmot tfjs_to_onnx.py",
                              opset_imports=[helper.make_opsetid("", 10)])
    model.ir_version = 6
    onnx.checker.check_model(model)
    onnx.save(model, out_onnx)
    with open(out_anchors, "w") as f:
        # Centre/size form: what the decoder needs, so C++ does no conversion.
        f.write("# SSD anchors of ssdlite_mobilenet_v2_coco: ycenter,xcenter,height,width (0..1)\n")
        for ymin, xmin, ymax, xmax in anchors.astype(np.float64):
            f.write(f"{(ymin + ymax) / 2:.9g},{(xmin + xmax) / 2:.9g},{ymax - ymin:.9g},"
                    f"{xmax - xmin:.9g}\n")
    print(f"wrote {out_onnx} ({len(g.onnx_nodes)} nodes) and {out_anchors} ({num} anchors)")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    try:
        convert(*sys.argv[1:])
    except (ConversionError, OSError, KeyError, ValueError) as e:
        sys.exit(f"tfjs_to_onnx.py: {e}")
