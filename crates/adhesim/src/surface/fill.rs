//! Filling the invalid points of a measured map by harmonic interpolation: the filled heights
//! solve the discrete Laplace equation Σ_{n ∈ N(p)} (h_n − h_p) = 0 at every invalid point p,
//! the valid points fixed. N(p) are the four nearest neighbours; on a free map the neighbours
//! past the edge are dropped (a vanishing normal derivative there). This is
//! SurfaceTopography's `interpolate_undefined_data` (1.27, `Uniform/Imputation.py`), which
//! solves the same sparse system directly; here it is solved by conjugate gradients (the
//! matrix is symmetric positive definite) to a relative residual of 1e-13.

use super::SurfaceError;

/// Relative residual ‖b − A·u‖/‖b‖ at which the conjugate gradients stop.
const TOLERANCE: f64 = 1e-13;

/// The heights with every invalid point replaced by the harmonic interpolation of the valid
/// ones (see the module). `valid[k]` is false at the points to fill; the valid heights are
/// returned unchanged. The grid's points are connected through their neighbours, so every
/// region of invalid points touches a valid one unless no point is valid (an error), and the
/// system is then positive definite. An error too if the iteration does not converge.
pub fn fill_invalid_harmonic(
    (nx, ny): (usize, usize),
    heights: &[f64],
    valid: &[bool],
    periodic: bool,
) -> Result<Vec<f64>, SurfaceError> {
    let count = nx * ny;
    if heights.len() != count || valid.len() != count {
        return Err(SurfaceError::SizeMismatch {
            expected: count,
            got: heights.len().min(valid.len()),
        });
    }
    let unknowns: Vec<usize> = (0..count).filter(|&k| !valid[k]).collect();
    let mut filled = heights.to_vec();
    if unknowns.is_empty() {
        return Ok(filled);
    }
    if unknowns.len() == count {
        return Err(SurfaceError::NoValidPoint);
    }
    let neighbours = |k: usize| -> [Option<usize>; 4] {
        let (ix, iy) = (k % nx, k / nx);
        let step = |i: usize, delta: isize, n: usize| -> Option<usize> {
            let j = i as isize + delta;
            if periodic {
                Some(j.rem_euclid(n as isize) as usize)
            } else {
                (0..n as isize).contains(&j).then_some(j as usize)
            }
        };
        [
            step(ix, -1, nx).map(|x| iy * nx + x),
            step(ix, 1, nx).map(|x| iy * nx + x),
            step(iy, -1, ny).map(|y| y * nx + ix),
            step(iy, 1, ny).map(|y| y * nx + ix),
        ]
    };
    // The equation is blind to a constant: solve for the deviations from the valid mean so
    // that the relative residual measures the roughness, not the map's offset.
    let valid_count = count - unknowns.len();
    let mean = (0..count).filter(|&k| valid[k]).map(|k| heights[k]).sum::<f64>() / valid_count as f64;
    // index of each unknown in the system, usize::MAX at valid points
    let mut index = vec![usize::MAX; count];
    for (i, &k) in unknowns.iter().enumerate() {
        index[k] = i;
    }
    // A·u with A = the negative Laplacian restricted to the unknowns (diagonal: the number
    // of neighbours inside the map), b = the sum of the valid neighbours' heights.
    let degree: Vec<f64> = unknowns
        .iter()
        .map(|&k| neighbours(k).iter().flatten().count() as f64)
        .collect();
    let rhs: Vec<f64> = unknowns
        .iter()
        .map(|&k| {
            neighbours(k)
                .iter()
                .flatten()
                .filter(|&&n| valid[n])
                .map(|&n| heights[n] - mean)
                .sum()
        })
        .collect();
    // Each unknown's invalid neighbours as unknowns' indices, in the order of `neighbours`
    // (so that the products below are summed in the same order): the stencil is looked up
    // once, not at every iteration.
    let mut offsets = Vec::with_capacity(unknowns.len() + 1);
    let mut links = Vec::with_capacity(4 * unknowns.len());
    offsets.push(0);
    for &k in &unknowns {
        links.extend(
            neighbours(k)
                .iter()
                .flatten()
                .filter(|&&n| !valid[n])
                .map(|&n| index[n]),
        );
        offsets.push(links.len());
    }
    let apply = |u: &[f64], out: &mut [f64]| {
        for (i, value) in out.iter_mut().enumerate() {
            let coupled: f64 = links[offsets[i]..offsets[i + 1]].iter().map(|&j| u[j]).sum();
            *value = degree[i] * u[i] - coupled;
        }
    };
    let solution = conjugate_gradients(&apply, &rhs, &degree)?;
    for (i, &k) in unknowns.iter().enumerate() {
        filled[k] = mean + solution[i];
    }
    Ok(filled)
}

/// Jacobi-preconditioned conjugate gradients for A·u = b (A symmetric positive definite,
/// its diagonal `diagonal`), from u = b / diagonal.
fn conjugate_gradients(
    apply: &dyn Fn(&[f64], &mut [f64]),
    rhs: &[f64],
    diagonal: &[f64],
) -> Result<Vec<f64>, SurfaceError> {
    let n = rhs.len();
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let rhs_norm = norm(rhs);
    let mut u: Vec<f64> = rhs.iter().zip(diagonal).map(|(b, d)| b / d).collect();
    if rhs_norm == 0.0 {
        return Ok(vec![0.0; n]);
    }
    let mut residual = vec![0.0; n];
    apply(&u, &mut residual);
    for (r, b) in residual.iter_mut().zip(rhs) {
        *r = b - *r;
    }
    let mut z: Vec<f64> = residual.iter().zip(diagonal).map(|(r, d)| r / d).collect();
    let mut direction = z.clone();
    let mut rz: f64 = residual.iter().zip(&z).map(|(r, z)| r * z).sum();
    let mut product = vec![0.0; n];
    // CG converges in at most n steps in exact arithmetic; rounding may need a few more.
    let max_iterations = 2 * n + 100;
    for _ in 0..max_iterations {
        if norm(&residual) <= TOLERANCE * rhs_norm {
            return Ok(u);
        }
        apply(&direction, &mut product);
        let curvature: f64 = direction.iter().zip(&product).map(|(p, q)| p * q).sum();
        let alpha = rz / curvature;
        for i in 0..n {
            u[i] += alpha * direction[i];
            residual[i] -= alpha * product[i];
            z[i] = residual[i] / diagonal[i];
        }
        let rz_next: f64 = residual.iter().zip(&z).map(|(r, z)| r * z).sum();
        let beta = rz_next / rz;
        rz = rz_next;
        for i in 0..n {
            direction[i] = z[i] + beta * direction[i];
        }
    }
    Err(SurfaceError::FillNotConverged {
        residual: norm(&residual) / rhs_norm,
    })
}
