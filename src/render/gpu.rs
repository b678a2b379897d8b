//! The wgpu backend (in progress).

pub struct GpuBackend;
impl GpuBackend {
    pub fn new() -> Result<Self, String> {
        Err("not yet".into())
    }
}
impl super::Backend for GpuBackend {
    fn name(&self) -> String {
        "wgpu".into()
    }
    fn render(
        &mut self,
        _: &super::scene::Scene,
        _: &[super::soft::ViewPrep],
        _: Option<f64>,
        _: &[[f64; 5]],
    ) -> Vec<(super::soft::SoftImage, super::soft::HardImage)> {
        unimplemented!()
    }
    fn loss(
        &mut self,
        _: &super::scene::Scene,
        _: &[super::soft::ViewPrep],
        _: f64,
        _: &[[f64; 5]],
        _: &[crate::fit::loss::Target],
        _: &crate::fit::loss::LossSpec,
        _: bool,
    ) -> super::LossOut {
        unimplemented!()
    }
}
