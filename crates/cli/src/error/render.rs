//! The renderer's errors as the CLI's: a scene or mesh file that does not exist and refused
//! output options are usage errors (exit 2); scene files, values, meshes and spectra that are
//! refused are data errors (exit 1). The message is the renderer's.

use super::CliError;
use specpoly_render::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> CliError {
        match e {
            Error::Formats(e) => e.into(),
            Error::Spectra(e) => e.into(),
            Error::Display(e) => e.into(),
            Error::Plot(e) => e.into(),
            Error::UnknownScene { .. }
            | Error::NoSuchSceneFile { .. }
            | Error::NoSuchMeshFile { .. }
            | Error::ExrSpace { .. }
            | Error::PngBits { .. }
            | Error::ImageFormat { .. } => CliError::usage(e.to_string()),
            Error::Toml { .. }
            | Error::Invalid { .. }
            | Error::Spectrum { .. }
            | Error::DepthLimit { .. }
            | Error::RayTree { .. }
            | Error::Mesh { .. }
            | Error::Convert(_) => CliError::data(e.to_string()),
        }
    }
}
