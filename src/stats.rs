//! Counters of the work a render did, reported by `--stats-json`.

/// Every counter is incremented where the work happens, never estimated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub pixels: u64,
    pub primary_rays: u64,
    /// Camera samples seen to miss the scene's box on the image
    /// ([`crate::render::footprint`]): the background, no ray cast.
    pub screen_culled: u64,
    pub shadow_rays: u64,
    pub reflected_rays: u64,
    pub refracted_rays: u64,
    /// Ray–primitive intersection calls.
    pub primitive_tests: u64,
    /// Ray–triangle tests inside meshes.
    pub triangle_tests: u64,
    /// GJK steps of rays cast against hulls and Minkowski sums.
    pub convex_steps: u64,
    /// Ray–bounding-box tests of CSG nodes.
    pub bound_tests: u64,
    /// Subtrees skipped because the ray missed their box.
    pub bound_culled: u64,
    pub normals_computed: u64,
    /// Queries whose span lists outgrew the thread's scratch buffer (each
    /// such query allocates once; see `csg::SCRATCH_SPANS`).
    pub span_allocations: u64,
    /// The longest span list any node produced.
    pub max_spans: u64,
    /// Samples whose colour was NaN or infinite (drawn black); always 0
    /// unless something is wrong.
    pub nonfinite_samples: u64,
    /// Nodes of the scene made by the certified approximation (set from
    /// the scene, not counted per ray).
    pub approximated_nodes: u64,
}

impl Stats {
    pub fn add(&mut self, o: &Stats) {
        self.pixels += o.pixels;
        self.primary_rays += o.primary_rays;
        self.screen_culled += o.screen_culled;
        self.shadow_rays += o.shadow_rays;
        self.reflected_rays += o.reflected_rays;
        self.refracted_rays += o.refracted_rays;
        self.primitive_tests += o.primitive_tests;
        self.triangle_tests += o.triangle_tests;
        self.convex_steps += o.convex_steps;
        self.bound_tests += o.bound_tests;
        self.bound_culled += o.bound_culled;
        self.normals_computed += o.normals_computed;
        self.span_allocations += o.span_allocations;
        self.max_spans = self.max_spans.max(o.max_spans);
        self.nonfinite_samples += o.nonfinite_samples;
        self.approximated_nodes = self.approximated_nodes.max(o.approximated_nodes);
    }
}
