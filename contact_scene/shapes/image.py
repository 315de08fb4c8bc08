"""A face read from a picture: dark pixels adhere."""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import ndimage

from ..errors import SceneError
from ..validation import flag, real
from . import numerical
from .base import Incircle, Shape

__all__ = ["ImageMask"]

#: ITU-R BT.601 luma weights: the grey level of an RGB pixel
_LUMA = np.array([0.299, 0.587, 0.114])


@dataclass(frozen=True)
class ImageMask(Shape):
    """A face read from an image: pixels darker than ``threshold`` belong to the face.

    Pixel (row 0, col 0) is the top-left corner; the image is centred on the origin, x to the
    right, y up.  Colour images are converted to grey by the ITU-R BT.601 luma weights.

    Parameters
    ----------
    path : str
        The image file (any format matplotlib reads).
    pixel_size : float, optional
        Side of one pixel in the scene's length unit, > 0; 1 by default.
    threshold : float, optional
        Grey level (0 black .. 1 white) below which a pixel belongs to the face; 0.5 by default.
    invert : bool, optional
        Light pixels belong to the face instead.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.path`` for an unreadable image or one without face pixels, or the
        parameter out of its range.
    """

    path: str = ""
    pixel_size: float = real(1.0, gt=0)
    threshold: float = real(0.5, ge=0, le=1)
    invert: bool = flag(False)
    kind = "image"

    def _complete(self):
        if not isinstance(self.path, (str, os.PathLike)) or not str(self.path):
            raise SceneError("indenter.path", f"must be the path of an image file (got {self.path!r})")
        if not np.any(self._mask):
            raise SceneError(
                "indenter.path",
                f"the image {self.path!r} has no face pixels (none darker than threshold={self.threshold:g})",
            )

    @cached_property
    def _mask(self) -> np.ndarray:
        import matplotlib.image as mpimg

        try:
            img = np.asarray(mpimg.imread(self.path), float)
        except (OSError, ValueError, SyntaxError) as exc:
            raise SceneError("indenter.path", f"cannot read image {self.path!r}: {exc}") from None
        if img.ndim == 3:
            rgb = img[..., :3]
            if img.dtype.kind in "ui" or rgb.max() > 1:
                rgb = rgb / 255.0
            # rounded: the weights' product for pure white is 0.9999999999999999, which a threshold
            # of 1 would count as face
            img = np.round(rgb @ _LUMA, 12)
        elif img.max() > 1:
            img = img / 255.0
        face = img < self.threshold
        if self.invert:
            face = ~face
        # rows run down the image; store as [ix, iy] with y up
        return np.ascontiguousarray(face[::-1, :].T)

    def contains(self, x, y):
        mask = self._mask
        nx, ny = mask.shape
        h = self.pixel_size
        ix = np.floor(np.asarray(x, float) / h + nx / 2).astype(np.int64)
        iy = np.floor(np.asarray(y, float) / h + ny / 2).astype(np.int64)
        in_image = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
        out = np.zeros(np.broadcast(ix, iy).shape, bool)
        out[in_image] = mask[ix[in_image], iy[in_image]]
        return out

    @property
    def area(self):
        return float(np.count_nonzero(self._mask)) * self.pixel_size**2

    @property
    def bounds(self):
        nx, ny = self._mask.shape
        h = self.pixel_size
        return (-nx * h / 2, -ny * h / 2, nx * h / 2, ny * h / 2)

    @property
    def centroid(self):
        ix, iy = np.nonzero(self._mask)
        nx, ny = self._mask.shape
        h = self.pixel_size
        return (float((ix.mean() + 0.5 - nx / 2) * h), float((iy.mean() + 0.5 - ny / 2) * h))

    def incircle(self):
        padded = np.pad(self._mask, 1)
        depth = ndimage.distance_transform_edt(padded)
        i = np.unravel_index(np.argmax(depth), depth.shape)
        nx, ny = self._mask.shape
        h = self.pixel_size
        c = ((i[0] - 1 + 0.5 - nx / 2) * h, (i[1] - 1 + 0.5 - ny / 2) * h)
        return Incircle(float((depth[i] - 0.5) * h), (float(c[0]), float(c[1])))

    def smallest_part_incircle(self):
        """The incircle of the image's narrowest island, which a grid must resolve.

        Islands are the 4-connected groups of face pixels (pixels touching only at a corner are
        apart); each island's incircle is found as :meth:`incircle` finds the whole face's, from
        the distance transform of the pixels: (depth - 1/2) pixels, exact for a square island and
        at most 0.21 pixel larger where the circle touches a pixel corner.  An image of one island
        gives its :meth:`incircle`.

        Returns
        -------
        Incircle
            Radius and centre, in the scene's length unit.
        """
        return self._smallest_part

    @cached_property
    def _smallest_part(self) -> Incircle:
        islands, depth, where = numerical.smallest_island(np.pad(self._mask, 1))
        if islands < 2:
            return self.incircle()
        nx, ny = self._mask.shape
        h = self.pixel_size
        c = ((where[0] - 1 + 0.5 - nx / 2) * h, (where[1] - 1 + 0.5 - ny / 2) * h)
        return Incircle(float((depth - 0.5) * h), (float(c[0]), float(c[1])))
