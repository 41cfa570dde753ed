//! What can go wrong reproducing the paper: a fit the core refuses, arguments that name the
//! wrong number of spectra, and the errors of the spectra named ([`specpoly_spectra::Error`])
//! and of the figures drawn ([`specpoly_plot::Error`]). Messages are one line; which errors are
//! the user's mistake (exit 2) is decided by the CLI.

/// An error of `specpoly-paper`.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Naming, reading or checking spectra, or a representation.
    #[error(transparent)]
    Spectra(#[from] specpoly_spectra::Error),
    /// Drawing a figure, or its size.
    #[error(transparent)]
    Plot(#[from] specpoly_plot::Error),
    /// A fit or colour the core refuses, for the spectrum or method named.
    #[error("{name}: {source}")]
    Fit {
        /// The spectrum or method.
        name: String,
        /// What the core says.
        source: specpoly_core::Error,
    },
    /// `--product` with other than two spectra.
    #[error("--product plots the product of two spectra; {given} given")]
    ProductNeedsTwo {
        /// How many were given.
        given: usize,
    },
    /// Table 1 of a name that holds several spectra.
    #[error("`{spec}` names {count} spectra; table1 takes one")]
    NotOneSpectrum {
        /// The name as given.
        spec: String,
        /// How many spectra it names.
        count: usize,
    },
}

impl Error {
    /// [`Error::Fit`] for `name`, as a `map_err` closure.
    pub(crate) fn fit(name: &str) -> impl FnOnce(specpoly_core::Error) -> Error + '_ {
        move |source| Error::Fit {
            name: name.to_string(),
            source,
        }
    }
}

/// The result type of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
