//! Shared Rust/GLSL structs with Rust as the single source of truth.
//!
//! A struct declared with [`gpu_struct!`] is `#[repr(C)]` and `bytemuck::Pod` (so the compiler
//! rejects hidden padding), and can print its own GLSL declaration. GLSL buffers that hold these
//! structs use `layout(scalar)` (GL_EXT_scalar_block_layout), whose rules equal `repr(C)` without
//! padding: every field's offset in GLSL is the Rust `offset_of!`. The generated headers live in
//! `shaders/include/generated/` and a test regenerates them and fails on any difference.

pub mod motion;
pub mod network;
pub mod params;
pub mod variants;

/// Rec.709 luma weights of linear RGB: every luminance in Blueshift (the metrics' `Y`, the
/// sorting key, the BRDF's lobe weights) uses these, in GLSL as
/// `REC709_LUMA_R/G/B` of the generated params header.
pub const REC709_LUMA: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// Rec.709 luminance of linear RGB, summed left to right (the order the GLSL twins use where
/// they must agree bit for bit).
#[inline]
pub fn luminance(rgb: [f32; 3]) -> f32 {
    REC709_LUMA[0] * rgb[0] + REC709_LUMA[1] * rgb[1] + REC709_LUMA[2] * rgb[2]
}

/// A Rust type with a GLSL spelling under scalar block layout.
///
/// Only 4-byte-aligned types are listed: glam's `Vec4`/`Mat4` are 16-byte aligned SIMD types
/// whose `repr(C)` padding would not match scalar layout; use `[f32; 4]` instead.
pub trait GlslType {
    /// GLSL base type name (`float`, `vec3`, a struct name, ...).
    fn glsl_base() -> String;
    /// Array suffix (`[4]`), empty for non-arrays.
    fn glsl_suffix() -> String {
        String::new()
    }
}

macro_rules! glsl_prim {
    ($($t:ty => $n:literal),* $(,)?) => { $(
        impl GlslType for $t { fn glsl_base() -> String { $n.to_string() } }
    )* };
}
glsl_prim!(
    f32 => "float", u32 => "uint", i32 => "int",
    glam::Vec2 => "vec2", glam::Vec3 => "vec3",
    glam::UVec2 => "uvec2", glam::UVec3 => "uvec3", glam::UVec4 => "uvec4",
    glam::IVec2 => "ivec2", glam::IVec3 => "ivec3", glam::IVec4 => "ivec4",
);

impl<T: GlslType, const N: usize> GlslType for [T; N] {
    fn glsl_base() -> String {
        T::glsl_base()
    }
    fn glsl_suffix() -> String {
        format!("[{N}]{}", T::glsl_suffix())
    }
}

/// One field of a shared struct, as reflected by [`gpu_struct!`].
#[derive(Debug, Clone)]
pub struct Field {
    pub name: &'static str,
    pub glsl_base: String,
    pub glsl_suffix: String,
    pub offset: usize,
    pub size: usize,
}

/// A struct shared between Rust and GLSL.
pub trait GpuStruct: bytemuck::Pod {
    const NAME: &'static str;
    fn fields() -> Vec<Field>;

    /// The GLSL declaration, with offsets and size in comments and a `<NAME>_SIZE` constant.
    fn glsl() -> String {
        let mut s = format!("struct {} {{\n", Self::NAME);
        for f in Self::fields() {
            s += &format!(
                "    {} {}{}; // offset {}, size {}\n",
                f.glsl_base, f.name, f.glsl_suffix, f.offset, f.size
            );
        }
        s += &format!(
            "}};\nconst uint {}_SIZE = {};\n",
            upper_snake(Self::NAME),
            std::mem::size_of::<Self>()
        );
        s
    }
}

impl<T: GpuStruct> GlslType for T {
    fn glsl_base() -> String {
        T::NAME.to_string()
    }
}

/// `BvhNode` -> `BVH_NODE`.
pub fn upper_snake(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_uppercase());
    }
    out
}

/// Builds a generated GLSL header: include guard, a do-not-edit banner, constants, structs.
#[derive(Debug, Default)]
pub struct Header {
    body: String,
}

impl Header {
    pub fn new() -> Self {
        Self::default()
    }
    /// Adds a struct declaration.
    pub fn push<T: GpuStruct>(mut self) -> Self {
        self.body += &T::glsl();
        self.body.push('\n');
        self
    }
    /// Adds a `const uint` shared with Rust.
    pub fn constant(mut self, name: &str, value: u32) -> Self {
        self.body += &format!("const uint {name} = {value}u;\n");
        self
    }
    /// Several `uint` constants, in order.
    pub fn constants<'a>(self, named: impl IntoIterator<Item = (&'a str, u32)>) -> Self {
        named
            .into_iter()
            .fold(self, |h, (name, value)| h.constant(name, value))
    }
    pub fn constant_i32(mut self, name: &str, value: i32) -> Self {
        self.body += &format!("const int {name} = {value};\n");
        self
    }
    /// A float constant, printed as the shortest decimal that parses back to the same f32.
    pub fn constant_f32(mut self, name: &str, value: f32) -> Self {
        self.body += &format!("const float {name} = {value:?};\n");
        self
    }
    /// The full header text for `shaders/include/generated/<file_stem>.glsl`.
    pub fn render(&self, file_stem: &str) -> String {
        let guard = format!("GENERATED_{}_GLSL", file_stem.to_ascii_uppercase());
        format!(
            "// GENERATED from Rust by blueshift-layout. Do not edit: regenerate with\n\
             // `cargo run -p blueshift-headers -- --write`.\n\
             #ifndef {guard}\n#define {guard}\n\n{}#endif\n",
            self.body
        )
    }
}

/// Declares a `#[repr(C)]`, `Pod` struct shared with GLSL.
///
/// ```
/// blueshift_layout::gpu_struct! {
///     /// Doc comments are kept.
///     pub struct Example { pub a: glam::Vec3, pub b: u32 }
/// }
/// use blueshift_layout::GpuStruct;
/// assert!(Example::glsl().contains("vec3 a; // offset 0, size 12"));
/// ```
#[macro_export]
macro_rules! gpu_struct {
    ($(#[$m:meta])* pub struct $name:ident { $($(#[$fm:meta])* pub $f:ident : $t:ty),* $(,)? }) => {
        $(#[$m])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $name { $($(#[$fm])* pub $f: $t),* }

        impl $crate::GpuStruct for $name {
            const NAME: &'static str = stringify!($name);
            fn fields() -> Vec<$crate::Field> {
                vec![$($crate::Field {
                    name: stringify!($f),
                    glsl_base: <$t as $crate::GlslType>::glsl_base(),
                    glsl_suffix: <$t as $crate::GlslType>::glsl_suffix(),
                    offset: core::mem::offset_of!($name, $f),
                    size: core::mem::size_of::<$t>(),
                }),*]
            }
        }
        // Scalar layout == repr(C) only when fields are packed in order with no gaps.
        const _: () = {
            let sum = 0 $(+ core::mem::size_of::<$t>())*;
            assert!(sum == core::mem::size_of::<$name>(), "gpu_struct has padding");
        };
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    gpu_struct! {
        pub struct Inner { pub x: u32, pub y: f32 }
    }
    gpu_struct! {
        pub struct Outer { pub p: glam::Vec3, pub inner: [Inner; 2], pub m: [f32; 4] }
    }

    #[test]
    fn offsets_follow_repr_c() {
        let f = Outer::fields();
        assert_eq!(f[0].offset, 0);
        assert_eq!(f[1].offset, 12);
        assert_eq!(f[1].glsl_base, "Inner");
        assert_eq!(f[1].glsl_suffix, "[2]");
        assert_eq!(f[2].offset, 28);
        assert_eq!(f[2].glsl_suffix, "[4]");
        assert_eq!(std::mem::size_of::<Outer>(), 28 + 16);
    }

    #[test]
    fn header_has_guard_and_constants() {
        let h = Header::new()
            .constant("MAX_X", 3)
            .push::<Inner>()
            .render("demo");
        assert!(h.contains("#ifndef GENERATED_DEMO_GLSL"));
        assert!(h.contains("const uint MAX_X = 3u;"));
        assert!(h.contains("const uint INNER_SIZE = 8;"));
    }
}
