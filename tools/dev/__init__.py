"""A developer's aids: galleries, surveys, OpenSCAD's own view, and the
explanation of shadow decisions two builds disagree on."""
