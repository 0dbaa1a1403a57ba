"""The first code cell every notebook starts with: imports and the helpers that read rtdr's EXRs (make_notebooks.py)."""

COMMON = '''import json, os, re, subprocess
import numpy as np
import matplotlib.pyplot as plt
import OpenImageIO as oiio

def read_exr(path):
    """All channels of a multi-layer EXR as a dict name -> 2D float array (docs/buffers.md)."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(f"cannot open {path}: {oiio.geterror()}")
    pixels = inp.read_image(format="float")
    names = list(inp.spec().channelnames)
    inp.close()
    return {name: pixels[..., k] for k, name in enumerate(names)}

def rgb(frame, layer):
    return np.stack([frame[f"{layer}.{c}"] for c in "RGB"], axis=-1)

def show(images, titles, cmap=None):
    fig, axes = plt.subplots(1, len(images), figsize=(4 * len(images), 2.6))
    for ax, image, title in zip(np.atleast_1d(axes), images, titles):
        ax.imshow(image, cmap=cmap)
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    plt.show()

def display(c):
    """Linear radiance to a viewable image: Reinhard c / (1 + c), then the sRGB curve."""
    c = np.clip(c / (1.0 + c), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)

def frame_index(name):
    """The index in a frame's file name: frame_0005.exr -> 5 (as many digits as there are)."""
    return int(re.fullmatch(r"frame_(\\d+)\\.exr", name).group(1))

def frame_files(folder):
    """The frames rtdr wrote into folder (frame_NNNN.exr), in order of their index."""
    return sorted((f for f in os.listdir(folder) if re.fullmatch(r"frame_\\d+\\.exr", f)), key=frame_index)'''
