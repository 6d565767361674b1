//! The fixture's module: `Shown` is exported, `Hidden` is not, and a method of `Shown` and a
//! field of it hand `Hidden` out.

pub struct Hidden;

pub struct Shown {
    pub inner: Hidden,
    count: u32,
}

impl Shown {
    pub fn hidden(&self) -> Hidden {
        Hidden
    }

    pub fn count(&self) -> u32 {
        self.count
    }
}
