//! Files in and out (feature `std`): parameter files in TOML, CSV output
//! (feature `csv`), in-memory recordings and SVG plots (feature `plot`).

#[cfg(feature = "csv")]
mod csv;
mod error;
mod names;
mod params;
#[cfg(feature = "plot")]
mod plot;
mod record;

#[cfg(feature = "csv")]
pub use self::csv::CsvWriter;
pub use error::{OutputError, ParameterError};
pub use params::{load_parameters, parameters_to_string, read_parameters, save_parameters};
#[cfg(feature = "plot")]
pub use plot::{
    Axes, Corner, Scale, Series, XySeries, svg_plot, write_svg_plot, write_xy_svg_plot, xy_svg_plot,
};
pub use record::{Column, LoggedEvent, Recording};
