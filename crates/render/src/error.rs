//! The renderer's errors: scenes that cannot be found, scene files and values refused, mesh
//! files that cannot be read, output options refused, and spectra that do not convert. The CLI
//! maps them to its messages and exit codes; the messages here are the whole text.

use std::path::PathBuf;

/// An error of the renderer.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene argument that is neither a file nor a built-in scene.
    #[error("unknown scene `{name}`: not a file, and not a built-in ({builtins})")]
    UnknownScene {
        /// The argument.
        name: String,
        /// The built-in scenes, comma-separated.
        builtins: String,
    },
    /// A scene argument that looks like a file name (`.toml`, a `/`) but is not a file.
    #[error("{name}: no such scene file")]
    NoSuchSceneFile {
        /// The argument.
        name: String,
    },
    /// A mesh file named in a scene file that does not exist.
    #[error("{at}: no such file {}", path.display())]
    NoSuchMeshFile {
        /// The scene file and the object naming it (`scene.toml: mesh 1 (bunny.obj)`).
        at: String,
        /// The file looked for.
        path: PathBuf,
    },
    /// A scene file that is not valid TOML or has unknown or mistyped keys; `message` is the
    /// one-line TOML error naming the file, line and column.
    #[error("{message}")]
    Toml {
        /// The message.
        message: String,
    },
    /// A value of a scene that is refused: `at` names the file and the value
    /// (`scene.toml: sphere 2`, `scene.toml: render.samples 17`), `why` what is wrong.
    #[error("{at}: {why}")]
    Invalid {
        /// The file and the value.
        at: String,
        /// What is wrong.
        why: String,
    },
    /// A spectrum of a scene that does not resolve (an unknown name, an unreadable file) or
    /// cannot be a reflectance.
    #[error("{what}: {error}")]
    Spectrum {
        /// The file and the value (`scene.toml: materials.red.diffuse`).
        what: String,
        /// Why, from the spectra crate.
        #[source]
        error: Box<specpoly_spectra::Error>,
    },
    /// `render.max_depth` above [`crate::budget::MAX_DEPTH`].
    #[error("{file}: render.max_depth {depth} is above the limit {limit}")]
    DepthLimit {
        /// The scene file.
        file: String,
        /// The depth asked for.
        depth: u32,
        /// The limit.
        limit: u32,
    },
    /// A worst-case ray tree above [`crate::budget::MAX_RAYS_PER_SAMPLE`].
    #[error(
        "{file}: render.max_depth {depth} with cutoff {cutoff} may trace {rays:.3e} rays per \
         sample (a material both reflects and transmits; the limit is {limit}): lower max_depth \
         or raise cutoff"
    )]
    RayTree {
        /// The scene file.
        file: String,
        /// `render.max_depth`.
        depth: u32,
        /// `render.cutoff`.
        cutoff: f32,
        /// The rays one sample may trace.
        rays: f64,
        /// The limit.
        limit: f64,
    },
    /// A mesh file (OBJ, PLY) that cannot be read or is refused.
    #[error("{file}: {why}")]
    Mesh {
        /// The file.
        file: String,
        /// What is wrong.
        why: String,
    },
    /// The scene's spectra do not convert to the colour representation.
    #[error("converting the scene's spectra: {0}")]
    Convert(#[source] specpoly_core::Error),
    /// `--exr-space` other than `rgb` or `xyz`.
    #[error("--exr-space `{given}`: use rgb or xyz")]
    ExrSpace {
        /// The value given.
        given: String,
    },
    /// A PNG depth other than 8 or 16 bits.
    #[error("--bits {bits}: PNG takes 8 or 16")]
    PngBits {
        /// The depth given.
        bits: u8,
    },
    /// An output image name whose extension is not `.png` or `.exr`.
    #[error("{}: {}", path.display(), match ext {
        Some(e) => format!("unknown image format `.{e}`: use .png or .exr"),
        None => "no file extension: use .png or .exr".to_string(),
    })]
    ImageFormat {
        /// The output image.
        path: PathBuf,
        /// Its extension, lower case (`None`: it has none).
        ext: Option<String>,
    },
    /// Reading or writing a file (`specpoly-formats`).
    #[error(transparent)]
    Formats(#[from] specpoly_formats::Error),
    /// Named spectra and representations (`specpoly-spectra`).
    #[error(transparent)]
    Spectra(#[from] specpoly_spectra::Error),
    /// The display an image is encoded for (`specpoly-display`).
    #[error(transparent)]
    Display(#[from] specpoly_display::Error),
    /// Text drawn into comparison images (`specpoly-plot`).
    #[error(transparent)]
    Plot(#[from] specpoly_plot::Error),
}

/// A result with the renderer's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// [`Error::Invalid`]: `at`, then `why`.
    pub(crate) fn invalid(at: impl std::fmt::Display, why: impl Into<String>) -> Self {
        Error::Invalid {
            at: at.to_string(),
            why: why.into(),
        }
    }
}
