// No view set: csgrt's own framing, and no notice about $vp*.
cube(10);
