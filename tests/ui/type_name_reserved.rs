// Type names that the generated code cannot use: the generic parameter `T`, Rust's
// primitive types, and the generated functions' argument names.
mod t {
    dynamics_runtime::mechanism! {
        pub struct T;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
    }
}
mod f {
    dynamics_runtime::mechanism! {
        pub struct f64;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
    }
}
mod q {
    dynamics_runtime::mechanism! {
        pub struct q;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
    }
}
mod l {
    dynamics_runtime::mechanism! {
        pub struct loads;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
        load push: force on b;
    }
}
mod u {
    dynamics_runtime::mechanism! {
        pub struct usize;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
    }
}
mod s {
    dynamics_runtime::mechanism! {
        pub struct str;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
    }
}

fn main() {}
