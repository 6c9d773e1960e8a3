"""Every figure of the package and the animation: the only folder that imports matplotlib."""
