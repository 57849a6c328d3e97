//! The models whose speed is measured (`examples/perf.rs` and `cargo bench
//! --bench derivatives`), and quiet user code for the satellite: thrusters
//! on a dead band, fixed commands (the cost of the model, not of user code).

pub mod models {
    autosim::model!(file = "examples/models/chain_spatial_1.sim");
    autosim::model!(file = "examples/models/chain_spatial_2.sim");
    autosim::model!(file = "examples/models/chain_spatial_3.sim");
    autosim::model!(file = "examples/models/chain_spatial_5.sim");
    autosim::model!(file = "examples/models/chain_spatial_7.sim");
    autosim::model!(file = "examples/models/chain_spatial_10.sim");
    autosim::model!(file = "examples/models/chain_spatial_20.sim");
    autosim::model!(file = "examples/models/chain_planar_10.sim");
    autosim::model!(file = "examples/models/satellite.sim");
    autosim::model!(file = "examples/models/satellite_small.sim");
    autosim::model!(file = "examples/models/four_bar.sim");
    autosim::model!(file = "examples/models/andrews.sim");
    autosim::model!(file = "examples/models/bicycle.sim");
    autosim::model!(
        file = "examples/models/chain_spatial_10.sim",
        name = ChainSpatial10Linear,
        linearize = true
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SatelliteLinear,
        linearize = true
    );
    autosim::model!(
        file = "examples/models/bicycle.sim",
        name = BicycleLinear,
        linearize = true
    );
    autosim::model!(
        file = "examples/models/chain_spatial_10.sim",
        name = ChainSpatial10Lanes,
        lanes = true
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SatelliteLanes,
        lanes = true
    );
}

include!("quiet.rs");

quiet!(
    models::satellite::Externs,
    models::satellite_small::Externs,
    models::satellite_linear::Externs,
    models::satellite_lanes::Externs
);
