//! What the generated items know of a model whether or not it derived: the
//! struct with its fields and constructor, and the vector and matrix types
//! of its size. Shared by [`emit`](super::emit) and the error stub.

use crate::model::Field;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;
use syn::{Attribute, Visibility};

/// The types of a model with `dof` coordinates, `constraints` holonomic
/// constraints and `inputs` control inputs.
pub struct Types {
    /// The number of coordinates, `N`.
    pub dof: usize,
    /// The number of holonomic constraints, `C`.
    pub constraints: usize,
    /// The number of control inputs, `K`.
    pub inputs: usize,
    /// The number of coordinates as a literal, `N`.
    pub n: Literal,
    /// The number of constraints, `C`.
    pub c: Literal,
    /// The number of inputs, `K`.
    pub k: Literal,
    /// `SVector<S, K>`.
    pub input_vector: TokenStream,
    /// `SMatrix<S, N, K>`.
    pub input_matrix: TokenStream,
    /// The constructor of `SMatrix<S, N, K>` from a column-major slice.
    pub new_input_matrix: TokenStream,
    /// `SVector<S, N>`.
    pub vector: TokenStream,
    /// `SMatrix<S, N, N>`.
    pub matrix: TokenStream,
    /// `SVector::<S, N>`, built from its entries by `api::stored`.
    pub new_vector: TokenStream,
    /// `SMatrix::<S, N, N>`, built from its entries by `api::stored`.
    pub new_matrix: TokenStream,
    /// `SVector<S, C>`.
    pub constraint_vector: TokenStream,
    /// `SMatrix<S, C, N>`.
    pub constraint_matrix: TokenStream,
    /// The constructor of `SVector<S, C>` from a slice.
    pub new_constraint_vector: TokenStream,
    /// The constructor of `SMatrix<S, C, N>` from a column-major slice.
    pub new_constraint_matrix: TokenStream,
    /// The number of contacts, `K` of `Contacts<N, K>`.
    pub contacts: usize,
    /// The number of contacts as a literal.
    pub kc: Literal,
    /// Per contact, whether its law gives its normal force (`normal:`).
    pub given_normals: Vec<bool>,
    /// Whether each contact's slip is a vector in the surface's plane.
    pub slip_planes: Vec<bool>,
    /// `SVector<S, K>`, `K` the number of contacts.
    pub contact_vector: TokenStream,
    /// `SMatrix<S, K, N>`.
    pub contact_matrix: TokenStream,
    /// The constructor of `SVector<S, K>` from a slice.
    pub new_contact_vector: TokenStream,
    /// The constructor of `SMatrix<S, K, N>` from a column-major slice.
    pub new_contact_matrix: TokenStream,
    /// `[S; L]`, `L` the number of `let` values.
    pub lets: TokenStream,
    /// `L`.
    pub let_count: Literal,
    /// `L`, as a number.
    pub let_total: usize,
    /// The number of parameter scalars, `P` (an indexed parameter `m[N]`
    /// counts `N`).
    pub parameters: usize,
    /// `SMatrix<S, N, P>`.
    pub parameter_matrix: TokenStream,
    /// The constructor of `SMatrix<S, N, P>` from a column-major slice.
    pub new_parameter_matrix: TokenStream,
    /// `SMatrix<S, C, P>`.
    pub constraint_parameter_matrix: TokenStream,
    /// The constructor of `SMatrix<S, C, P>` from a column-major slice.
    pub new_constraint_parameter_matrix: TokenStream,
    /// The number of lumped parameters of the regressor, `K`.
    pub regressors: usize,
    /// `SMatrix<S, N, K>`.
    pub regressor_matrix: TokenStream,
    /// `SVector<S, K>`.
    pub regressor_vector: TokenStream,
    /// The axes `D` of a model whose masses hang on a tree of increments
    /// (`derive::articulated`), zero for the others.
    pub articulated_axes: usize,
}

impl Types {
    /// The types of a model of this size, with `lets` values.
    pub fn new(dof: usize, constraints: usize, inputs: usize, lets: usize) -> Self {
        let na = nalgebra();
        let n = Literal::usize_unsuffixed(dof);
        let c = Literal::usize_unsuffixed(constraints);
        let k = Literal::usize_unsuffixed(inputs);
        Types {
            dof,
            constraints,
            inputs,
            input_vector: quote!(#na::SVector<S, #k>),
            input_matrix: quote!(#na::SMatrix<S, #n, #k>),
            new_input_matrix: quote!(#na::SMatrix::<S, #n, #k>::from_column_slice),
            k,
            vector: quote!(#na::SVector<S, #n>),
            matrix: quote!(#na::SMatrix<S, #n, #n>),
            new_vector: quote!(#na::SVector::<S, #n>),
            new_matrix: quote!(#na::SMatrix::<S, #n, #n>),
            constraint_vector: quote!(#na::SVector<S, #c>),
            constraint_matrix: quote!(#na::SMatrix<S, #c, #n>),
            new_constraint_vector: quote!(#na::SVector::<S, #c>::from_column_slice),
            new_constraint_matrix: quote!(#na::SMatrix::<S, #c, #n>::from_column_slice),
            contacts: 0,
            kc: Literal::usize_unsuffixed(0),
            given_normals: Vec::new(),
            slip_planes: Vec::new(),
            contact_vector: quote!(#na::SVector<S, 0>),
            contact_matrix: quote!(#na::SMatrix<S, 0, #n>),
            new_contact_vector: quote!(#na::SVector::<S, 0>::from_column_slice),
            new_contact_matrix: quote!(#na::SMatrix::<S, 0, #n>::from_column_slice),
            lets: {
                let l = Literal::usize_unsuffixed(lets);
                quote!([S; #l])
            },
            let_count: Literal::usize_unsuffixed(lets),
            let_total: lets,
            parameters: 0,
            parameter_matrix: quote!(#na::SMatrix<S, #n, 0>),
            new_parameter_matrix: quote!(#na::SMatrix::<S, #n, 0>::from_column_slice),
            constraint_parameter_matrix: quote!(#na::SMatrix<S, #c, 0>),
            new_constraint_parameter_matrix: quote!(#na::SMatrix::<S, #c, 0>::from_column_slice),
            regressors: 0,
            regressor_matrix: quote!(#na::SMatrix<S, #n, 0>),
            regressor_vector: quote!(#na::SVector<S, 0>),
            articulated_axes: 0,
            n,
            c,
        }
    }

    /// The same types for a model whose regressor has `k` lumped
    /// parameters.
    pub fn with_regressor(mut self, k: usize) -> Self {
        let na = nalgebra();
        let (n, kk) = (&self.n, Literal::usize_unsuffixed(k));
        self.regressor_matrix = quote!(#na::SMatrix<S, #n, #kk>);
        self.regressor_vector = quote!(#na::SVector<S, #kk>);
        self.regressors = k;
        self
    }

    /// The same types for a model whose masses hang on a tree of
    /// increments in `axes` axes (zero: not).
    pub fn with_articulated(mut self, axes: usize) -> Self {
        self.articulated_axes = axes;
        self
    }

    /// The same types for a model with `parameters` parameter scalars.
    pub fn with_parameters(mut self, parameters: usize) -> Self {
        let na = nalgebra();
        let (n, p) = (&self.n, Literal::usize_unsuffixed(parameters));
        self.parameter_matrix = quote!(#na::SMatrix<S, #n, #p>);
        self.new_parameter_matrix = quote!(#na::SMatrix::<S, #n, #p>::from_column_slice);
        let c = &self.c;
        self.constraint_parameter_matrix = quote!(#na::SMatrix<S, #c, #p>);
        self.new_constraint_parameter_matrix = quote!(#na::SMatrix::<S, #c, #p>::from_column_slice);
        self.parameters = parameters;
        self
    }

    /// Whether each contact's slip is a vector in the surface's plane.
    pub fn with_slip_planes(mut self, slip_planes: &[bool]) -> Self {
        self.slip_planes = slip_planes.to_vec();
        self
    }

    /// The same types for a model with contacts, `given_normals` saying of
    /// each whether its law gives its normal force.
    pub fn with_contacts(mut self, given_normals: &[bool]) -> Self {
        let contacts = given_normals.len();
        self.given_normals = given_normals.to_vec();
        let na = nalgebra();
        let (n, k) = (&self.n, Literal::usize_unsuffixed(contacts));
        self.contact_vector = quote!(#na::SVector<S, #k>);
        self.contact_matrix = quote!(#na::SMatrix<S, #k, #n>);
        self.new_contact_vector = quote!(#na::SVector::<S, #k>::from_column_slice);
        self.new_contact_matrix = quote!(#na::SMatrix::<S, #k, #n>::from_column_slice);
        self.contacts = contacts;
        self.kc = k;
        self
    }
}

/// A parameter's domain as the runtime's `Domain` (`Domain::REAL` for
/// none), a constant expression.
pub fn domain_tokens(domain: Option<crate::ast::Domain>) -> TokenStream {
    let Some(d) = domain else {
        return quote!(::lagrange::Domain::REAL);
    };
    let bound = |x: f64| {
        if x == f64::INFINITY {
            quote!(::core::f64::INFINITY)
        } else if x == f64::NEG_INFINITY {
            quote!(::core::f64::NEG_INFINITY)
        } else {
            let abs = Literal::f64_unsuffixed(x.abs());
            if x < 0.0 { quote!(-#abs) } else { quote!(#abs) }
        }
    };
    let (lo, hi, lc, uc) = (
        bound(d.lower),
        bound(d.upper),
        d.lower_closed,
        d.upper_closed,
    );
    quote!(::lagrange::Domain::new(#lo, #lc, #hi, #uc))
}

/// The path of nalgebra in generated code.
pub fn nalgebra() -> TokenStream {
    quote!(::lagrange::nalgebra)
}

/// The path of the runtime's sine and cosine (`lagrange::trig`), which the
/// generated code calls for every `sin` and `cos`.
pub fn trig() -> TokenStream {
    quote!(::lagrange::trig)
}

/// What the generated items know of a model whether or not it derived: its
/// struct's attributes, visibility, name and fields, and its size.
pub struct Outline<'a> {
    /// The user's attributes on the struct.
    pub attrs: &'a [Attribute],
    /// The struct's visibility.
    pub vis: &'a Visibility,
    /// The struct's name.
    pub name: &'a Ident,
    /// The number of coordinates.
    pub dof: usize,
    /// The runtime parameters' fields, in declaration order: the arguments of `new`.
    pub fields: &'a [Field],
    /// The control inputs' fields (after the parameters'), which `new` does
    /// not take: they start unset (NaN).
    pub inputs: &'a [Field],
    /// The number of contacts (0 for a model without `contacts:`).
    pub contacts: usize,
    /// The number of holonomic constraints (0 for a model in minimal
    /// coordinates, which then has no constraint items).
    pub constraints: usize,
    /// `#[lagrange(serde)]`.
    pub serde: bool,
    /// `#[lagrange(parameter_derivatives)]`.
    pub parameter_derivatives: bool,
    /// `#[lagrange(regressor(..))]`: the lumped parameters' names (empty
    /// strings in the stub, one per listed scalar).
    pub regressor: Option<&'a [String]>,
    /// The number of `let` values.
    pub lets: usize,
}

impl Outline<'_> {
    /// `struct Name<S = f64> { pub field: S, ... }`, with the user's
    /// attributes; a model without parameters holds a `PhantomData`.
    pub fn struct_item(&self) -> TokenStream {
        let Outline {
            attrs, vis, name, ..
        } = self;
        let fields = if self.fields.is_empty() && self.inputs.is_empty() {
            quote!({ _scalar: ::core::marker::PhantomData<S> })
        } else {
            let params = self.fields.iter().map(|f| {
                let (name, ty) = (&f.name, f.rust_type());
                let doc = match f.len {
                    None => format!(" The parameter `{name}`."),
                    Some(len) => format!(" The parameters `{name}[0..{len}]`."),
                };
                quote!(#[doc = #doc] pub #name: #ty,)
            });
            let inputs = self.inputs.iter().map(|f| {
                let (name, ty) = (&f.name, f.rust_type());
                let skip = self.serde.then(|| {
                    // Inputs are set during a run: not part of a scene's
                    // parameters, and read back unset (NaN).
                    let unset = match f.len {
                        None => "::lagrange::inputs::unset::<S>".to_string(),
                        Some(len) => format!("::lagrange::inputs::unset_array::<S, {len}>"),
                    };
                    quote!(#[serde(skip, default = #unset)])
                });
                let doc = match f.len {
                    None => format!(" The control input `{name}`: NaN until set (`set_inputs`, `with_inputs` or a controller)."),
                    Some(len) => format!(" The control inputs `{name}[0..{len}]`: NaN until set (`set_inputs`, `with_inputs` or a controller)."),
                };
                quote!(#[doc = #doc] #skip pub #name: #ty,)
            });
            quote!({ #(#params)* #(#inputs)* })
        };
        let serde = self.serde.then(|| {
            quote! {
                #[derive(::lagrange::serde::Serialize, ::lagrange::serde::Deserialize)]
                #[serde(
                    crate = "::lagrange::serde",
                    bound(
                        serialize = "S: ::lagrange::serde::Serialize",
                        deserialize = "S: ::lagrange::serde::Deserialize<'de> \
                                       + ::lagrange::nalgebra::RealField + ::core::marker::Copy"
                    )
                )]
            }
        });
        // The fields are named as the user named the parameters and inputs,
        // as physics writes them (`R`, `Omega`, `I1`): no `non_snake_case`
        // warning in the user's crate for names the user chose.
        quote! {
            #(#attrs)*
            #[derive(Clone, Copy, Debug, PartialEq)]
            #[allow(non_snake_case)]
            #serde
            #vis struct #name<S = f64> #fields
        }
    }

    /// `const fn new(fields) -> Self`. A model with inputs gets a plain
    /// `fn`: its inputs start as NaN ("not set", which the runtime refuses
    /// to integrate), and a NaN of a generic `S` is not a constant.
    pub fn constructor(&self) -> TokenStream {
        let params: Vec<&Ident> = self.fields.iter().map(|f| &f.name).collect();
        let types = self.fields.iter().map(Field::rust_type);
        if !self.inputs.is_empty() {
            let na = nalgebra();
            let nan = quote!(#na::convert::<f64, S>(::core::f64::NAN));
            let inputs = self.inputs.iter().map(|f| {
                let name = &f.name;
                match f.len {
                    None => quote!(#name: #nan),
                    Some(len) => {
                        let len = Literal::usize_unsuffixed(len);
                        quote!(#name: [#nan; #len])
                    }
                }
            });
            return quote!(fn new(#(#params: #types),*) -> Self { Self { #(#params,)* #(#inputs,)* } });
        }
        let body = if params.is_empty() {
            quote!(Self {
                _scalar: ::core::marker::PhantomData
            })
        } else {
            quote!(Self { #(#params,)* })
        };
        quote!(const fn new(#(#params: #types),*) -> Self { #body })
    }

    /// The parameters by name, for a model with parameters: the struct
    /// `NameParameters<S>` with a field per parameter, and the checked
    /// constructors `try_new` (positional) and `from_parameters` (by
    /// name), which refuse a value outside its declared domain, with
    /// `check_parameters`, their check, and `parameters`, the struct read
    /// back off a model. Bounded by `RealField` (a value is
    /// compared with its domain's ends), where `new` takes any scalar.
    pub fn by_name(&self) -> TokenStream {
        if self.fields.is_empty() {
            return TokenStream::new();
        }
        let na = nalgebra();
        let (vis, name) = (self.vis, self.name);
        let parameters = quote::format_ident!("{}Parameters", name);
        let params: Vec<&Ident> = self.fields.iter().map(|f| &f.name).collect();
        let types: Vec<TokenStream> = self.fields.iter().map(Field::rust_type).collect();
        let fields = self.fields.iter().zip(&types).map(|(f, ty)| {
            let field = &f.name;
            let doc = match f.domain {
                None => format!(" `{field}`."),
                Some(d) => format!(" `{field} {}`.", d.written()),
            };
            quote!(#[doc = #doc] pub #field: #ty,)
        });
        let checks = self.fields.iter().filter_map(|f| {
            let d = f.domain?;
            let (field, label) = (&f.name, f.name.to_string());
            let domain = domain_tokens(Some(d));
            Some(match f.len {
                None => quote!(#domain.check(#label, ::core::option::Option::None, self.#field)?;),
                Some(_) => quote!(#domain.check_all(#label, &self.#field)?;),
            })
        });
        let doc = format!(
            " The parameters of [`{name}`] by name, for [`{name}::from_parameters`]: each field \
             the parameter of that name (with its domain, where it declares one)."
        );
        let error = quote!(::lagrange::ParameterError);
        quote! {
            #[doc = #doc]
            #[derive(Clone, Copy, Debug, PartialEq)]
            #[allow(non_snake_case)]
            #vis struct #parameters<S = f64> { #(#fields)* }

            #[allow(non_snake_case, clippy::all)]
            impl<S: #na::RealField + ::core::marker::Copy> #name<S> {
                /// `new`, each parameter checked against its declared domain: the first
                /// outside it is the error, named with its value.
                pub fn try_new(#(#params: #types),*) -> ::core::result::Result<Self, #error> {
                    let model = Self::new(#(#params),*);
                    model.check_parameters()?;
                    ::core::result::Result::Ok(model)
                }
                /// The model from its parameters by name, each checked against its declared
                /// domain (as `try_new`).
                pub fn from_parameters(parameters: #parameters<S>) -> ::core::result::Result<Self, #error> {
                    Self::try_new(#(parameters.#params),*)
                }
                /// Whether every parameter lies inside its declared domain: the first that
                /// does not is the error (after a field was set, or a model was read back).
                pub fn check_parameters(&self) -> ::core::result::Result<(), #error> {
                    #(#checks)*
                    ::core::result::Result::Ok(())
                }
            }

            #[allow(non_snake_case, clippy::all)]
            impl<S: ::core::marker::Copy> #name<S> {
                /// The model's parameters by name: with `..model.parameters()`, a model that
                /// differs from this one in the parameters named.
                pub fn parameters(&self) -> #parameters<S> {
                    #parameters { #(#params: self.#params),* }
                }
            }
        }
    }

    /// The constructor's doc: the parameters in order.
    pub fn constructor_doc(&self) -> String {
        let parameters: Vec<String> = self
            .fields
            .iter()
            .map(|f| match f.len {
                None => format!("`{}`", f.name),
                Some(len) => format!("`{}: [S; {len}]`", f.name),
            })
            .collect();
        let mut doc = format!(
            "A `{}` with the given parameters ({}).",
            self.name,
            if parameters.is_empty() {
                "none".to_string()
            } else {
                parameters.join(", ")
            }
        );
        if !self.inputs.is_empty() {
            doc.push_str(
                " Its control inputs start unset (NaN): set them with `with_inputs` or drive them \
                 with `with_controller` before integrating.",
            );
        }
        if self.fields.iter().any(|f| f.domain.is_some()) {
            doc.push_str(
                " The parameters' domains are not checked here (`new` takes any scalar, SIMD \
                 lanes and constants included): `try_new` and `from_parameters` check them.",
            );
        }
        doc
    }
}
