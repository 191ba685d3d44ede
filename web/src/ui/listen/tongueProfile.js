// The tongue's mid-sagittal curve for any parameters, without the scene: the rig's evaluator
// (core/tongue.js), the collision correction against the palate and teeth when the tables are
// there (so that a blended tongue does not show through the palate), and the curve at z = 0
// (SagittalPanel.js). The listening page draws the target's and the learner's estimated tongue
// with it; both go through the same steps, so they differ only by their parameters.

import { correctVertices } from '../../core/collision.js';
import { TongueRig } from '../../core/tongue.js';
import { sagittalCurve } from '../shared/SagittalPanel.js';

export class TongueProfile {

	/**
	 * @param {object} definition the tongue rig definition (GET /tongue/rig)
	 * @param {object|null} tables decoded collision tables, or null for no correction
	 */
	constructor( definition, tables = null ) {

		this.rig = new TongueRig( definition );
		this.tables = tables;
		this.surface = this.rig.createSurface();
		this.values = new Float64Array( this.rig.parameterCount );

	}

	/**
	 * The curve of `params` ({ name: value }; names the rig does not know are left out, values
	 * outside a range are held at its end): x y per station, closed, into `target`.
	 * @param {Float64Array} [target] 2 * stationCount
	 */
	curve( params, target = new Float64Array( 2 * this.rig.stationCount ) ) {

		const rig = this.rig;
		this.values.set( rig.neutral );
		for ( const [ name, value ] of Object.entries( params ?? {} ) ) {

			const k = rig.parameterIndex.get( name );
			if ( k === undefined || ! Number.isFinite( value ) ) continue;
			this.values[ k ] = Math.min( rig.maximum[ k ], Math.max( rig.minimum[ k ], value ) );

		}

		rig.evaluate( this.values, this.surface, false );
		if ( this.tables ) correctVertices( this.surface.positions, rig.vertexCount, this.tables, null, null );
		return sagittalCurve( rig, this.surface.positions, target );

	}

}
