//! Where `mpw verify` finds its reference data: one folder given at run time
//! (`mpw verify --data DIR`, default `data`, the repository's), so a copied binary runs
//! the table from anywhere. The folder holds `materials/` (parameter sets), `scenes/`,
//! `experiments/` (the default synthetic set, the 304L and 945 experiment files). The
//! real records those experiment files name lie in the shared data folder beside the
//! repository (`DIR/../../shared/data`, the path the files themselves use); the rows on
//! them run only when it is there.

use std::path::{Path, PathBuf};

#[derive(Debug, Clone)]
pub struct VerifyData {
    root: PathBuf,
}

impl VerifyData {
    pub fn new(root: impl Into<PathBuf>) -> Self {
        VerifyData { root: root.into() }
    }

    /// The repository's `data/` folder, for tests.
    pub fn repository() -> Self {
        Self::new(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data"))
    }

    /// The folder of material parameter files.
    pub fn materials(&self) -> PathBuf {
        self.root.join("materials")
    }

    /// The folder of shipped scenes.
    pub fn scenes(&self) -> PathBuf {
        self.root.join("scenes")
    }

    /// The MPM-level synthetic's data, F2 of the 3D quarter (`mpw synth --shpb-3d`).
    pub fn mpm_synthetic_data(&self) -> PathBuf {
        self.root.join("experiments/mpm_synthetic_f2.csv")
    }

    /// The shipped synthetic experiment set (`mpw fit`'s default).
    pub fn default_set(&self) -> PathBuf {
        self.root.join("experiments/default.toml")
    }

    /// The shared real-data folder the experiment files point into.
    pub fn shared_root(&self) -> PathBuf {
        self.root.join("../../shared/data")
    }

    /// A folder of the shared real data, if it is beside the repository.
    fn shared(&self, folder: &str) -> Option<PathBuf> {
        let dir = self.shared_root().join(folder);
        dir.is_dir().then_some(dir)
    }

    /// The all-records 304L set, if its records are there.
    pub fn ss304l_set(&self) -> Option<PathBuf> {
        self.shared("tension/304L")?;
        Some(self.root.join("experiments/fit_304l.toml"))
    }

    /// The six-record 945-steel set (single point), if its records are there.
    pub fn steel_945_set(&self) -> Option<PathBuf> {
        self.shared("shpb/steel_945")?;
        Some(self.root.join("experiments/fit_945.toml"))
    }

    /// The measured-velocity SHPB scene of 945 test 01, if its record is there.
    pub fn steel_945_scene(&self) -> Option<PathBuf> {
        self.shared("shpb/steel_945")?;
        Some(
            self.root
                .join("scenes/shpb/945_test01_measured_velocity.toml"),
        )
    }

    /// The experiment files of the six 945-steel SHPB records, if the records are there.
    pub fn steel_945(&self) -> Option<Vec<PathBuf>> {
        self.shared("shpb/steel_945")?;
        let folder = self.root.join("experiments/shpb_steel_945");
        Some(
            (1..=6)
                .map(|i| folder.join(format!("test_0{i}.toml")))
                .collect(),
        )
    }
}
